/* lexer.c: tokens with positions; see lexer.h for the rules. */
#include "lexer.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decimal.h"

/* Longest part of a token quoted in a message; the rest becomes "...". */
#define QUOTE_MAX 32

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' ||
           c == '\f';
}

/* Ends a word or a malformed number. */
static int is_delim(char c)
{
    return is_space(c) || c == '#' || c == '\0';
}

/* The UTF-8 byte-order mark that Windows editors put before the text. */
static const char utf8_bom[3] = {'\xef', '\xbb', '\xbf'};

int lexer_init(struct lexer *lx, const char *text, size_t len)
{
    memset(lx, 0, sizeof *lx);
    if (len >= sizeof utf8_bom && memcmp(text, utf8_bom, sizeof utf8_bom) == 0) {
        text += sizeof utf8_bom; /* not part of the text: column 1 follows it */
        len -= sizeof utf8_bom;
    }
    lx->line = 1;
    lx->col = 1;
    if (len == SIZE_MAX) /* no room for the NUL */
        return -1;
    lx->buf = malloc(len + 1);
    if (!lx->buf)
        return -1;
    if (len > 0)
        memcpy(lx->buf, text, len);
    lx->buf[len] = '\0';
    lx->len = len;
    return 0;
}

void lexer_free(struct lexer *lx)
{
    free(lx->buf);
    lx->buf = NULL;
    lx->len = 0;
    lx->pos = 0;
}

/* Moves n bytes on, keeping line and column. */
static void advance(struct lexer *lx, size_t n)
{
    for (size_t i = 0; i < n && lx->pos < lx->len; i++) {
        if (lx->buf[lx->pos++] == '\n') {
            lx->line++;
            lx->col = 1;
        } else {
            lx->col++;
        }
    }
}

/* Skips white space and comments. A comment stops at a NUL byte too, so
 * that a NUL anywhere is reported. */
static void skip_blank(struct lexer *lx)
{
    while (lx->pos < lx->len) {
        char c = lx->buf[lx->pos];
        if (is_space(c)) {
            advance(lx, 1);
        } else if (c == '#') {
            while (lx->pos < lx->len && lx->buf[lx->pos] != '\n' &&
                   lx->buf[lx->pos] != '\0')
                advance(lx, 1);
        } else {
            break;
        }
    }
}

/* Bytes strtod reads as a number at pos (0 if none), and its value. Only a
 * digit, sign or '.' may begin a number: a word such as "nan" or "info" is
 * a word, so a parser can name it. */
static size_t number_length(const struct lexer *lx, size_t pos, double *value)
{
    if (pos >= lx->len || !strchr("0123456789+-.", lx->buf[pos]) ||
        lx->buf[pos] == '\0')
        return 0;
    char *end = NULL;
    double v = decimal_read(lx->buf + pos, &end);
    size_t n = (size_t)(end - (lx->buf + pos));
    if (pos + n > lx->len) /* cannot happen: buf[len] is NUL */
        n = lx->len - pos;
    if (value)
        *value = v;
    return n;
}

/* End of the run of non-delimiter bytes starting at pos. */
static size_t run_end(const struct lexer *lx, size_t pos)
{
    while (pos < lx->len && !is_delim(lx->buf[pos]))
        pos++;
    return pos;
}

/* Makes *tok the sticky error token; message gets the quoted bytes. */
static void fail(struct lexer *lx, struct token *tok, size_t len,
                 const char *what, const char *suffix)
{
    char quoted[LEXER_QUOTE_SIZE];
    lexer_quote(tok->text, len, quoted, sizeof quoted);
    snprintf(lx->message, sizeof lx->message, "%s%s%s", what, quoted, suffix);
    tok->kind = TOKEN_ERROR;
    tok->len = len;
    lx->failed = 1;
    lx->error = *tok;
}

static void lex_word(struct lexer *lx, struct token *tok)
{
    size_t end = run_end(lx, lx->pos);
    tok->kind = TOKEN_WORD;
    tok->len = end - lx->pos;
    advance(lx, tok->len);
}

/* A number of n bytes starts at pos. What follows must end it: a delimiter
 * or the start of another number ("1-10"); anything else ("1abc") makes the
 * whole run malformed. */
static void lex_number(struct lexer *lx, struct token *tok, size_t n,
                       double value)
{
    size_t after = lx->pos + n;
    if (after < lx->len && !is_delim(lx->buf[after]) &&
        number_length(lx, after, NULL) == 0) {
        fail(lx, tok, run_end(lx, lx->pos) - lx->pos, "malformed number ", "");
        return;
    }
    if (!isfinite(value)) {
        fail(lx, tok, n, "expected a finite number, found ", "");
        return;
    }
    tok->kind = TOKEN_NUMBER;
    tok->len = n;
    tok->value = value;
    advance(lx, n);
}

void lexer_next(struct lexer *lx, struct token *tok)
{
    if (lx->failed) {
        *tok = lx->error;
        return;
    }
    skip_blank(lx);
    memset(tok, 0, sizeof *tok);
    tok->line = lx->line;
    tok->col = lx->col;
    tok->text = lx->buf + lx->pos;
    if (lx->pos >= lx->len) {
        tok->kind = TOKEN_EOF;
        return;
    }
    if (lx->buf[lx->pos] == '\0') {
        fail(lx, tok, 1, "unexpected character ", "");
        return;
    }
    double value = 0;
    size_t n = number_length(lx, lx->pos, &value);
    if (n == 0)
        lex_word(lx, tok);
    else
        lex_number(lx, tok, n, value);
}

void lexer_rescan_word(struct lexer *lx, struct token *tok)
{
    if (tok->kind == TOKEN_EOF || tok->text[0] == '\0')
        return;
    lx->pos = (size_t)(tok->text - lx->buf);
    lx->line = tok->line;
    lx->col = tok->col;
    lx->failed = 0;
    lex_word(lx, tok);
}

int token_is_nonfinite_word(const struct token *tok)
{
    if (tok->kind != TOKEN_WORD || tok->len == 0)
        return 0;
    /* The word ends at a delimiter inside the NUL-terminated copy, and no
     * form strtod accepts crosses one, so this stays inside the word. */
    char *end = NULL;
    double v = strtod(tok->text, &end);
    return (size_t)(end - tok->text) == tok->len && !isfinite(v);
}

/* Appends s to out[*used..size), always leaving a NUL. */
static void append(char *out, size_t size, size_t *used, const char *s)
{
    size_t n = strlen(s);
    if (*used + 1 >= size)
        return;
    if (n > size - 1 - *used)
        n = size - 1 - *used;
    memcpy(out + *used, s, n);
    *used += n;
    out[*used] = '\0';
}

/* One byte as a message shows it: itself if printable ASCII, else \xNN. */
static void escape_byte(unsigned char c, char piece[8])
{
    if (c >= 0x20 && c < 0x7f)
        snprintf(piece, 8, "%c", c);
    else
        snprintf(piece, 8, "\\x%02x", c);
}

void lexer_quote(const char *s, size_t len, char *out, size_t size)
{
    size_t used = 0;
    if (size == 0)
        return;
    out[0] = '\0';
    append(out, size, &used, "'");
    size_t shown = len < QUOTE_MAX ? len : QUOTE_MAX;
    for (size_t i = 0; i < shown; i++) {
        char piece[8];
        escape_byte((unsigned char)s[i], piece);
        append(out, size, &used, piece);
    }
    if (shown < len)
        append(out, size, &used, "...");
    append(out, size, &used, "'");
}

void keyword_list(const char *const *words, int n, char *out, size_t size)
{
    size_t used = 0;
    if (size == 0)
        return;
    out[0] = '\0';
    for (int i = 0; i < n; i++) {
        append(out, size, &used, i == 0 ? "'" : i == n - 1 ? " or '" : ", '");
        append(out, size, &used, words[i]);
        append(out, size, &used, "'");
    }
}

char *lexer_escape(const char *s)
{
    size_t n = strlen(s);
    if (n > (SIZE_MAX - 1) / 4)
        return NULL;
    char *out = malloc(4 * n + 1); /* every byte may become \xNN */
    if (!out)
        return NULL;
    size_t used = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        char piece[8];
        escape_byte((unsigned char)s[i], piece);
        append(out, 4 * n + 1, &used, piece);
    }
    return out;
}

void token_describe(const struct token *tok, char *out, size_t size)
{
    if (tok->kind == TOKEN_EOF) {
        snprintf(out, size, "end of file");
        return;
    }
    lexer_quote(tok->text, tok->len, out, size);
}
