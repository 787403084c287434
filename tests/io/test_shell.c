/* dfl_shell_quote: the exact words for plain and quoted names, and the
 * rule itself -- every shell reads the word back as the same bytes --
 * checked by running sh (and bash, dash when present) on all 255 one-byte
 * strings and on hostile names. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/shell.h"
#include "util/tmpdir.h"

Test(shell, exact_words)
{
    static const char *const cases[][2] = {
        {"abc", "abc"},
        {"/work/a-b_c.ini", "/work/a-b_c.ini"},
        {"x=1,2:3+4@5%6", "x=1,2:3+4@5%6"},
        {"", "''"},
        {"a b", "'a b'"},
        {"it's", "'it'\\''s'"},
        {"'", "''\\'''"},
        {"$(touch P)", "'$(touch P)'"},
        {"a\nb", "'a\nb'"},
        {"~", "'~'"},
        {"*", "'*'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *q = dfl_shell_quote(cases[i][0]);
        cr_assert_not_null(q);
        cr_expect_str_eq(q, cases[i][1], "quote(%s)", cases[i][0]);
        char *buf = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&buf, &len);
        cr_assert_not_null(m);
        dfl_shell_put(m, cases[i][0]);
        fclose(m);
        cr_expect_str_eq(buf, q, "put and quote agree on %s", cases[i][0]);
        free(buf);
        free(q);
    }
}

#define NWORDS (255 + 8)

/* Runs `SHELL script` where script is `printf '%s\0' WORD...` and checks
 * that the output is the words' bytes, each followed by a NUL. */
static void round_trip(const char *shell)
{
    char sh[64];
    snprintf(sh, sizeof sh, "/bin/%s", shell);
    FILE *probe = fopen(sh, "r");
    if (!probe) {
        cr_log_warn("%s not installed: skipped", sh);
        return;
    }
    fclose(probe);
    char *words[NWORDS];
    size_t nw = 0;
    for (int c = 1; c <= 255; c++) {
        words[nw] = calloc(2, 1);
        words[nw++][0] = (char)c;
    }
    static const char *const hostile[] = {
        "x\ntouch PWNED\n.ini", "a b  c", "$(touch PWNED)", "`touch PWNED`", "'\"'\"",
        "100%", "\\\\n\\", "\xff\xfe not utf-8 {} *",
    };
    for (size_t i = 0; i < 8; i++) words[nw++] = strdup(hostile[i]);
    char dir[256], script[512], outp[512], cmd[1400];
    tmpdir_new(dir, sizeof dir);
    snprintf(script, sizeof script, "%s/s.sh", dir);
    snprintf(outp, sizeof outp, "%s/out", dir);
    FILE *fp = fopen(script, "wb");
    cr_assert_not_null(fp);
    fputs("printf '%s\\0'", fp);
    for (size_t i = 0; i < nw; i++) {
        fputc(' ', fp);
        dfl_shell_put(fp, words[i]);
    }
    fputc('\n', fp);
    fclose(fp);
    snprintf(cmd, sizeof cmd, "cd '%s' && %s s.sh > out", dir, sh);
    cr_assert_eq(system(cmd), 0, "%s failed on the script", sh);
    fp = fopen(outp, "rb");
    cr_assert_not_null(fp);
    static char got[1 << 16];
    const size_t n = fread(got, 1, sizeof got, fp);
    fclose(fp);
    size_t at = 0;
    for (size_t i = 0; i < nw; i++) {
        const size_t l = strlen(words[i]);
        cr_expect(at + l < n && memcmp(got + at, words[i], l) == 0 && got[at + l] == '\0',
                  "%s: word %zu (first byte 0x%02x) read back differently", shell, i,
                  (unsigned char)words[i][0]);
        at += l + 1;
        free(words[i]);
    }
    cr_expect_eq(at, n, "%s: %zu bytes out, %zu expected", shell, n, at);
    cr_expect_eq(tmpdir_count(dir), 2, "%s: a command in a word ran (files: %d)", shell,
                 tmpdir_count(dir));
    tmpdir_remove(dir);
}

Test(shell, every_shell_reads_the_same_bytes)
{
    round_trip("sh");
    round_trip("bash");
    round_trip("dash");
}
