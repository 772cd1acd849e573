/* lexer.c: tokens with positions; see lexer.h for the rules. */
#include "lexer.h"

#include <errno.h>
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

/* The window keeps LOOKAHEAD bytes from each token's start (or all that is
 * left): a whole token of up to LEXER_TOKEN_MAX bytes, and past it the few
 * bytes strtod looks at before it settles ("1e+" is 1 once it sees what
 * follows), so no token is ever cut by where a read stopped. A refill
 * reads at least CHUNK bytes. */
#define LOOKAHEAD (LEXER_TOKEN_MAX + 16)
#define CHUNK ((size_t)1 << 16)

/* Reads from the source into buf[len..cap); sets eof at its end. */
static void read_more(struct lexer *lx)
{
    size_t room = lx->cap - lx->len, n;
    if (lx->file) {
        errno = 0;
        n = fread(lx->buf + lx->len, 1, room, lx->file);
        if (n < room) { /* fread stops short only at the end or an error */
            lx->eof = 1;
            if (ferror(lx->file))
                lx->read_errno = errno ? errno : EIO;
        }
    } else {
        n = lx->mem_len - lx->mem_pos < room ? lx->mem_len - lx->mem_pos : room;
        if (n > 0)
            memcpy(lx->buf + lx->len, lx->mem + lx->mem_pos, n);
        lx->mem_pos += n;
        lx->eof = lx->mem_pos == lx->mem_len;
    }
    lx->len += n;
    lx->buf[lx->len] = '\0';
}

/* Makes buf hold LOOKAHEAD bytes from pos, or the rest of the text, by
 * dropping what comes before pos and reading on. */
static void fill(struct lexer *lx)
{
    if (lx->eof || lx->len - lx->pos >= LOOKAHEAD)
        return;
    memmove(lx->buf, lx->buf + lx->pos, lx->len - lx->pos);
    lx->len -= lx->pos;
    lx->pos = 0;
    read_more(lx);
}

static int start(struct lexer *lx)
{
    lx->line = 1;
    lx->col = 1;
    lx->cap = LOOKAHEAD + CHUNK;
    lx->buf = malloc(lx->cap + 1);
    lx->text[0] = malloc(LEXER_TOKEN_MAX + 2);
    lx->text[1] = malloc(LEXER_TOKEN_MAX + 2);
    if (!lx->buf || !lx->text[0] || !lx->text[1]) {
        errno = ENOMEM;
        return -1;
    }
    lx->text[0][0] = lx->text[1][0] = '\0';
    read_more(lx);
    if (lx->read_errno) {
        errno = lx->read_errno;
        return -1;
    }
    if (lx->len >= sizeof utf8_bom && memcmp(lx->buf, utf8_bom, sizeof utf8_bom) == 0)
        lx->pos = sizeof utf8_bom; /* not part of the text: column 1 follows it */
    return 0;
}

int lexer_init_text(struct lexer *lx, const char *text, size_t len)
{
    memset(lx, 0, sizeof *lx);
    lx->mem = text;
    lx->mem_len = len;
    return start(lx);
}

int lexer_init_file(struct lexer *lx, FILE *f)
{
    memset(lx, 0, sizeof *lx);
    lx->file = f;
    return start(lx);
}

void lexer_free(struct lexer *lx)
{
    free(lx->buf);
    free(lx->text[0]);
    free(lx->text[1]);
    lx->buf = lx->text[0] = lx->text[1] = NULL;
    lx->len = lx->pos = 0;
}

/* Moves n bytes on (all in the window), keeping line and column. */
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

/* Skips white space and comments, reading on as needed. A comment stops
 * at a NUL byte too, so that a NUL anywhere is reported. */
static void skip_blank(struct lexer *lx)
{
    int comment = 0;
    for (;;) {
        if (lx->pos == lx->len) {
            fill(lx);
            if (lx->pos == lx->len)
                return;
        }
        char c = lx->buf[lx->pos];
        if (c == '#')
            comment = 1;
        else if (c == '\n')
            comment = 0;
        else if (c == '\0' || (!comment && !is_space(c)))
            return;
        advance(lx, 1);
    }
}

/* Bytes strtod reads as a number at pos (0 if none), and its value. Only a
 * digit, sign or '.' may begin a number: a word such as "nan" or "info" is
 * a word, so a parser can name it. */
static size_t number_length(const struct lexer *lx, size_t pos, double *value)
{
    if (pos >= lx->len)
        return 0;
    char c = lx->buf[pos];
    if (!(c >= '0' && c <= '9') && c != '+' && c != '-' && c != '.')
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

/* Gives *tok (at pos) its text: a copy of len bytes, kept while the
 * window moves on. An error token's is cut after LEXER_TOKEN_MAX + 1. */
static void set_text(struct lexer *lx, struct token *tok, size_t len)
{
    if (len > LEXER_TOKEN_MAX + 1)
        len = LEXER_TOKEN_MAX + 1;
    char *t = lx->text[lx->slot];
    memcpy(t, lx->buf + lx->pos, len);
    t[len] = '\0';
    tok->text = t;
    tok->len = len;
}

/* Makes *tok the sticky error token of len bytes at pos; message gets
 * what, the quoted bytes, then suffix. */
static void fail(struct lexer *lx, struct token *tok, size_t len,
                 const char *what, const char *suffix)
{
    char quoted[LEXER_QUOTE_SIZE];
    set_text(lx, tok, len);
    lexer_quote(tok->text, tok->len, quoted, sizeof quoted);
    snprintf(lx->message, sizeof lx->message, "%s%s%s", what, quoted, suffix);
    tok->kind = TOKEN_ERROR;
    lx->failed = 1;
    lx->error = *tok;
}

static void fail_long(struct lexer *lx, struct token *tok, size_t len)
{
    char suffix[64];
    snprintf(suffix, sizeof suffix, " is longer than %d bytes", LEXER_TOKEN_MAX);
    fail(lx, tok, len, "token ", suffix);
}

static void lex_word(struct lexer *lx, struct token *tok)
{
    size_t n = run_end(lx, lx->pos) - lx->pos;
    if (n > LEXER_TOKEN_MAX) {
        fail_long(lx, tok, n);
        return;
    }
    tok->kind = TOKEN_WORD;
    set_text(lx, tok, n);
    advance(lx, n);
}

/* A number of n bytes starts at pos. What follows must end it: a delimiter
 * or the start of another number ("1-10"); anything else ("1abc") makes the
 * whole run malformed. */
static void lex_number(struct lexer *lx, struct token *tok, size_t n,
                       double value)
{
    size_t after = lx->pos + n;
    if (n > LEXER_TOKEN_MAX) {
        fail_long(lx, tok, n);
        return;
    }
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
    tok->value = value;
    set_text(lx, tok, n);
    /* No newline to count: a number is what strtod reads from a digit,
     * sign or '.', and it skips white space only before all of these. */
    lx->pos += n;
    lx->col += n;
}

void lexer_next(struct lexer *lx, struct token *tok)
{
    if (lx->failed) {
        *tok = lx->error;
        return;
    }
    skip_blank(lx);
    fill(lx); /* the whole token is in the window from here on */
    memset(tok, 0, sizeof *tok);
    lx->slot ^= 1;
    lx->tok_pos = lx->pos;
    tok->line = lx->line;
    tok->col = lx->col;
    set_text(lx, tok, 0);
    if (lx->read_errno) { /* at the token where the text stopped */
        snprintf(lx->message, sizeof lx->message, "cannot read further: %s",
                 strerror(lx->read_errno));
        tok->kind = TOKEN_ERROR;
        lx->failed = 1;
        lx->error = *tok;
        return;
    }
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
    if (tok->kind == TOKEN_EOF || tok->text[0] == '\0' || lx->read_errno)
        return;
    lx->pos = lx->tok_pos;
    lx->line = tok->line;
    lx->col = tok->col;
    lx->failed = 0;
    lex_word(lx, tok);
}

int token_is_nonfinite_word(const struct token *tok)
{
    if (tok->kind != TOKEN_WORD || tok->len == 0)
        return 0;
    /* The word's copy ends with a NUL, and no form strtod accepts crosses
     * a delimiter, so this stays inside the word. */
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
