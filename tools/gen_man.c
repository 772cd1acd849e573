/* gen_man.c: writes the man page tp2.1 from the --help text (usage.h), so
 * the two never disagree. Build-time tool: gen_man OUTPUT.
 *
 * usage.h's shape: "usage: tp2 SYNOPSIS", a paragraph, then sections
 * ("heading:") of items (two spaces, a term, two or more spaces, text;
 * lines indented further continue the item's text). */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "usage.h"

#ifndef TP2_VERSION
#define TP2_VERSION "unknown"
#endif

/* Text as roff shows it literally: backslashes and minus signs escaped, a
 * line never starting with a control character. */
static void put_text(FILE *f, const char *s, size_t n, int line_start)
{
    if (line_start && n > 0 && (s[0] == '.' || s[0] == '\''))
        fputs("\\&", f);
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\\')
            fputs("\\e", f);
        else if (s[i] == '-')
            fputs("\\-", f);
        else
            fputc(s[i], f);
    }
}

/* An item's term: its first word bold (the option), the rest italic. */
static void put_term(FILE *f, const char *s, size_t n)
{
    size_t word = strcspn(s, " ");
    if (word > n)
        word = n;
    fputs(".TP 22\n\\fB", f);
    put_text(f, s, word, 0);
    fputs("\\fR", f);
    if (word < n) {
        fputs(" \\fI", f);
        put_text(f, s + word + 1, n - word - 1, 0);
        fputs("\\fR", f);
    }
    fputc('\n', f);
}

/* One line of usage.h (without its newline). */
static void put_line(FILE *f, const char *s, size_t n, int *described)
{
    if (n == 0)
        return;
    if (strncmp(s, "usage: ", 7) == 0) {
        fputs(".SH SYNOPSIS\n.B tp2\n", f);
        put_text(f, s + 11, n - 11, 1); /* after "usage: tp2 " */
        fputc('\n', f);
    } else if (s[0] != ' ' && s[n - 1] == ':') {
        fputs(".SH ", f);
        for (size_t i = 0; i + 1 < n; i++)
            fputc(toupper((unsigned char)s[i]), f);
        fputc('\n', f);
    } else if (s[0] != ' ') {
        if (!*described)
            fputs(".SH DESCRIPTION\n", f);
        *described = 1;
        put_text(f, s, n, 1);
        fputc('\n', f);
    } else if (n > 2 && s[2] != ' ') {
        const char *gap = strstr(s + 2, "  ");
        size_t term = gap && (size_t)(gap - s) < n ? (size_t)(gap - s) - 2 : n - 2;
        put_term(f, s + 2, term);
        const char *text = s + 2 + term;
        while (text < s + n && *text == ' ')
            text++;
        put_text(f, text, (size_t)(s + n - text), 1);
        fputc('\n', f);
    } else {
        const char *text = s;
        while (text < s + n && *text == ' ')
            text++;
        put_text(f, text, (size_t)(s + n - text), 1);
        fputc('\n', f);
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fputs("usage: gen_man OUTPUT\n", stderr);
        return 2;
    }
    FILE *f = fopen(argv[1], "w");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    fputs(".\\\" Generated from host/app/usage.h by tools/gen_man.c; do not edit.\n"
          ".TH TP2 1 \"\" \"tp2 " TP2_VERSION "\" \"User Commands\"\n"
          ".SH NAME\ntp2 \\- a Whitted ray tracer on Vulkan compute\n", f);
    const char *text = TP2_USAGE_TEXT;
    int described = 0;
    while (*text) {
        size_t n = strcspn(text, "\n");
        put_line(f, text, n, &described);
        text += n + (text[n] == '\n');
    }
    fputs(".SH SEE ALSO\nREADME.TXT in the source tree: the scene format, choices, "
          "troubleshooting.\n", f);
    if (fclose(f) != 0) {
        perror(argv[1]);
        return 1;
    }
    return 0;
}
