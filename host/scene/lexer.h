/* lexer.h: splits scene text into numbers and words, with positions.
 *
 * Numbers are read the way C's strtod reads them (C locale), one after
 * another, so "1-10 5" is 1, -10, 5 and "2.5.3" is 2.5, .3. A token that does
 * not begin a number is a word and runs to the next white space, '#' or NUL.
 * '#' starts a comment that runs to the end of the line.
 *
 * The text streams through a window of bounded size (about 128 KiB), from
 * a file or from memory alike: memory follows the scene, not the size of
 * the input, and an error shows as soon as the text does (docs/format.md). So a token is at most LEXER_TOKEN_MAX bytes long. */
#ifndef TP2_LEXER_H
#define TP2_LEXER_H

#include <stddef.h>
#include <stdio.h>

enum token_kind { TOKEN_EOF, TOKEN_NUMBER, TOKEN_WORD, TOKEN_ERROR };

struct token {
    enum token_kind kind;
    const char *text; /* len bytes and a NUL, owned by the lexer: valid until
                       * lexer_next has been called twice more (the token a
                       * one-token-lookahead parser holds, and the one before) */
    size_t len;
    size_t line, col; /* 1-based; col counts bytes, so a tab is one column */
    double value;     /* TOKEN_NUMBER only; always finite */
};

/* Longest token: a longer one is an error at its start, so that no token
 * can make the window grow. Far above any number or file name. */
#define LEXER_TOKEN_MAX 65536

/* Room for a quoted token: 32 bytes escaped as \xNN, quotes, "...", NUL. */
#define LEXER_QUOTE_SIZE 144
/* Room for a lexical error message such as "malformed number '...'": the
 * longest lead-in, a quoted token and a 64-byte suffix always fit, so no
 * message is ever cut (and GCC's -O3 -Wformat-truncation can tell). */
#define LEXER_MESSAGE_SIZE 256

struct lexer {
    FILE *file;        /* the source: a stream (not owned) ... */
    const char *mem;   /* ... or memory */
    size_t mem_len, mem_pos;
    char *buf;         /* the window: text from the current token on; buf[len]
                        * is a NUL, so strtod stops inside it */
    size_t cap, len, pos;
    size_t tok_pos;    /* where in buf the last token began (rescans) */
    int eof;           /* the source has given all it has */
    int read_errno;    /* why reading stopped early; 0 if it did not */
    char *text[2];     /* copies of the last two tokens' text */
    int slot;          /* the one holding the last token */
    size_t line, col;
    int failed;                 /* errors are sticky: the same token again */
    struct token error;         /* the TOKEN_ERROR token, once failed */
    char message[LEXER_MESSAGE_SIZE]; /* what went wrong, once failed */
};

/* Positions the lexer at the start of len bytes of text (need not be NUL
 * terminated; may hold NUL bytes), which must stay unchanged until
 * lexer_free; or of the stream f, which the caller closes after lexer_free.
 * A UTF-8 byte-order mark at the start is skipped, so line 1, column 1 is
 * the first byte after it. Returns 0, or -1 with errno set: ENOMEM, or why
 * the first read failed (EISDIR for a folder); lexer_free is safe then. A
 * later read error is a TOKEN_ERROR where the text stopped. */
int lexer_init_text(struct lexer *lx, const char *text, size_t len);
int lexer_init_file(struct lexer *lx, FILE *f);

/* Frees the window; safe after a failed lexer_init_* and twice. */
void lexer_free(struct lexer *lx);

/* Stores the next token in *tok. At the end it gives TOKEN_EOF (positioned
 * just past the last byte) forever. On a lexical error (NUL byte, malformed or
 * non-finite number, a token longer than LEXER_TOKEN_MAX, a read error) it
 * gives TOKEN_ERROR with lx->message set, and then the same token forever. */
void lexer_next(struct lexer *lx, struct token *tok);

/* Reads again, as a word, the token *tok that lexer_next just gave (a
 * number, a word or an error), so that a file name such as "1.ppm" or
 * "2x.bmp" is one word; a lexical error there is forgotten. At the end of
 * the text, at a NUL byte or a read error, *tok stays what it was. */
void lexer_rescan_word(struct lexer *lx, struct token *tok);

/* 1 if tok is a word that strtod reads whole as infinity or NaN ("inf",
 * "NaN", "Infinity"), so a parser can say a finite number was expected. */
int token_is_nonfinite_word(const struct token *tok);

/* Writes s[0..len) to out in single quotes, bytes outside printable ASCII
 * as \xNN, at most 32 bytes of it and then "...". Always NUL-terminates
 * out (when size > 0); LEXER_QUOTE_SIZE is always enough. */
void lexer_quote(const char *s, size_t len, char *out, size_t size);

/* Writes "'a', 'b' or 'c'" for the n words, for "expected ..." messages. */
void keyword_list(const char *const *words, int n, char *out, size_t size);

/* A new string: s with every byte outside printable ASCII written as
 * \xNN, as lexer_quote shows tokens, but never cut; for file names in
 * messages. NULL when out of memory. */
char *lexer_escape(const char *s);

/* What a message says was found: "end of file" or the quoted token. */
void token_describe(const struct token *tok, char *out, size_t size);

#endif
