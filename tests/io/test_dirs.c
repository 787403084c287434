/* io/dirs: which folders a run may replace (derived from what the header
 * states: a dflab manifest listing every other entry), which names can be
 * results folders, the swap, the restore of a cut-off replacement's
 * backup, and the probe that leaves nothing. */
#define _DEFAULT_SOURCE /* realpath */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/dirs.h"
#include "io/manifest.h"
#include "util/tmpdir.h"

/* A results folder as dflab writes it: two data files and a manifest
 * (format magic when magic, else the shape before it existed). */
static void make_results(const char *dir, int magic)
{
    char p[600];
    mkdir(dir, 0755);
    tmpdir_write(dir, "a.csv", "x\n1\n", p, sizeof p);
    tmpdir_write(dir, "config.ini", "[study]\n", p, sizeof p);
    dfl_manifest *m = dfl_manifest_new();
    cr_assert_not_null(m);
    if (magic) cr_assert_eq(dfl_manifest_put_format(m), DFL_OK);
    cr_assert_eq(dfl_manifest_put_string(m, "tool", "dflab"), DFL_OK);
    dfl_err err;
    snprintf(p, sizeof p, "%s/manifest.json", dir);
    cr_assert_eq(dfl_manifest_write(m, p, dir, &err), DFL_OK);
    dfl_manifest_free(m);
}

static void expect_refused(const char *dir, const char *word)
{
    dfl_err err;
    dfl_err_clear(&err);
    cr_expect_eq(dfl_dir_check_replaceable(dir, "manifest.json", "--out", &err), DFL_E_INPUT,
                 "%s accepted", dir);
    cr_expect(strstr(err.msg, dir) && strstr(err.msg, word), "message lacks %s / %s: %s", dir,
              word, err.msg);
}

static void expect_ok(const char *dir)
{
    dfl_err err;
    dfl_err_clear(&err);
    cr_expect_eq(dfl_dir_check_replaceable(dir, "manifest.json", "--out", &err), DFL_OK, "%s: %s",
                 dir, err.msg);
}

Test(dirs, replaceable_only_when_every_entry_is_listed)
{
    char t[256], d[512], p[600];
    tmpdir_new(t, sizeof t);
    snprintf(d, sizeof d, "%s/o", t);
    expect_ok(d); /* missing */
    mkdir(d, 0755);
    expect_ok(d); /* empty */
    make_results(d, 1);
    expect_ok(d);
    tmpdir_write(d, "notes.txt", "mine\n", p, sizeof p);
    expect_refused(d, "notes.txt");
    unlink(p);
    snprintf(p, sizeof p, "%s/a.csv", d); /* a listed name that is not a regular file */
    unlink(p);
    mkdir(p, 0755);
    expect_refused(d, "a.csv");
    rmdir(p);
    expect_ok(d); /* a listed file missing: nothing foreign */
    /* a newer format version, someone else's manifest */
    snprintf(p, sizeof p, "%s/manifest.json", d);
    FILE *fp = fopen(p, "wb");
    fputs("{\n  \"format\": \"dflab-results\",\n  \"format_version\": 2,\n  \"files\": [\n  ]\n}\n", fp);
    fclose(fp);
    expect_refused(d, "not a dflab results manifest");
    tmpdir_write(d, "manifest.json", "{\"name\": \"webapp\", \"files\": []}\n", p, sizeof p);
    expect_refused(d, "not a dflab results manifest");
    tmpdir_remove(d);
    /* no manifest: the first entry by name is named */
    mkdir(d, 0755);
    tmpdir_write(d, "zz", "", p, sizeof p);
    tmpdir_write(d, "index.html", "", p, sizeof p);
    expect_refused(d, "no manifest.json; it holds index.html");
    tmpdir_remove(d);
    /* a link to a dflab folder: the swap would replace the link */
    make_results(d, 1);
    char ln[600];
    snprintf(ln, sizeof ln, "%s/ln", t);
    cr_assert_eq(symlink(d, ln), 0);
    expect_refused(ln, "symbolic link");
    unlink(ln);
    tmpdir_remove(d);
    /* the shape before the magic is accepted when all entries match */
    make_results(d, 0);
    expect_ok(d);
    tmpdir_write(d, "extra", "", p, sizeof p);
    expect_refused(d, "extra");
    tmpdir_remove(t);
}

Test(dirs, results_files_reads_names_and_refuses_the_rest)
{
    char t[256], p[600];
    tmpdir_new(t, sizeof t);
    static const char *const names[] = {"a \"q\"", "b\\c", "d\ne", "\xc3\xa9t\xc3\xa9"};
    for (int i = 0; i < 4; i++) tmpdir_write(t, names[i], "x", p, sizeof p);
    dfl_manifest *m = dfl_manifest_new();
    dfl_manifest_put_format(m);
    dfl_err err;
    snprintf(p, sizeof p, "%s/manifest.json", t);
    cr_assert_eq(dfl_manifest_write(m, p, t, &err), DFL_OK);
    dfl_manifest_free(m);
    char *json = dfl_file_read_all(p, NULL);
    cr_assert_not_null(json);
    char **got;
    size_t n;
    cr_assert_eq(dfl_manifest_results_files(json, &got, &n), 1);
    cr_assert_eq(n, 4);
    /* the writer sorts by strcmp: "a..." "b..." "d..." then the UTF-8 one */
    for (size_t i = 0; i < n; i++) {
        cr_expect_str_eq(got[i], names[i]);
        free(got[i]);
    }
    free(got);
    /* every truncation of the text before its closing brace is refused,
     * and none reads past its end (the copy is exactly as long as the
     * prefix); only the final newline may go */
    const size_t len = strlen(json);
    cr_assert(len > 2 && strcmp(json + len - 2, "}\n") == 0);
    for (size_t k = 0; k < len - 1; k++) {
        char *cut = malloc(k + 1);
        memcpy(cut, json, k);
        cut[k] = '\0';
        cr_expect_eq(dfl_manifest_results_files(cut, &got, &n), -1, "prefix of %zu bytes", k);
        cr_expect_null(got);
        free(cut);
    }
    cr_expect_eq(dfl_manifest_results_files("{\n  \"format\": \"dflab-results\",\n  "
                                            "\"format_version\": 1,\n  \"files\": [\n  ]\n}\njunk",
                                            &got, &n), -1);
    cr_expect_eq(dfl_manifest_results_files("{\n  \"format\": \"dflab-results\",\n  "
                                            "\"format_version\": 1,\n  \"files\": [\n    "
                                            "{\"name\": \"a\\u00\"}\n  ]\n}\n", &got, &n), -1);
    free(json);
    tmpdir_remove(t);
}

/* The manifest is read as JSON, not as one spelling: the members may come
 * in any order and with any white space; the magic, the version and the
 * shape of "files" are what decide. */
Test(dirs, results_files_is_json_not_a_spelling)
{
    char **got;
    size_t n;
    static const char *const yes1[] = {
        "{\"files\":[{\"sha256\":\"00\",\"name\":\"a\"}],\"format_version\":1,"
        "\"format\":\"dflab-results\"}",
        " {\"format\" : \"dflab-results\" , \"format_version\" : 1 , \"files\" : "
        "[ { \"name\" : \"\\u0061\" } ] } \n",
    };
    for (size_t i = 0; i < 2; i++) {
        cr_assert_eq(dfl_manifest_results_files(yes1[i], &got, &n), 1, "%s", yes1[i]);
        cr_assert_eq(n, 1);
        cr_expect_str_eq(got[0], "a");
        free(got[0]);
        free(got);
    }
    cr_assert_eq(dfl_manifest_results_files("{\"tool\":\"dflab\",\"files\":[]}", &got, &n), 0);
    cr_expect_eq(n, 0);
    cr_expect_null(got);
    static const char *const no[] = {
        "{\"format\":\"dflab-results\",\"format_version\":2,\"files\":[]}",
        "{\"format\":\"dflab-resultz\",\"format_version\":1,\"files\":[]}",
        "{\"format\":\"dflab-results\",\"format_version\":1.0,\"files\":[]}",
        "{\"format\":\"dflab-results\",\"files\":[]}",
        "{\"format\":\"dflab-results\",\"format_version\":1}",
        "{\"format\":\"dflab-results\",\"format_version\":1,\"files\":{}}",
        "{\"format\":\"dflab-results\",\"format_version\":1,\"files\":[\"a\"]}",
        "{\"format\":\"dflab-results\",\"format_version\":1,\"files\":[{\"name\":1}]}",
        "{\"format\":\"dflab-results\",\"format_version\":1,\"files\":[{\"name\":\"\\u0000\"}]}",
        "{\"format\":\"dflab-results\",\"format_version\":1,\"files\":[],\"files\":[]}",
        "{\"format\":\"dflab-results\",\"format_version\":1,\"files\":[],}",
        "{\"tool\":\"dflab\",\"format\":\"x\",\"files\":[]}",
        "{\"tool\":\"dflabx\",\"files\":[]}",
        "[{\"tool\":\"dflab\",\"files\":[]}]",
    };
    for (size_t i = 0; i < sizeof no / sizeof no[0]; i++) {
        cr_expect_eq(dfl_manifest_results_files(no[i], &got, &n), -1, "%s", no[i]);
        cr_expect_null(got);
        cr_expect_eq(n, 0);
    }
}

Test(dirs, names_that_cannot_be_results_folders)
{
    char t[256], d[600];
    tmpdir_new(t, sizeof t);
    dfl_err err;
    static const char *const bad[] = {".", "..", "./", "a/.", "a/..", "a/./", "/tmp/..", "x/../."};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        cr_expect_eq(dfl_dir_check_name(bad[i], "--out", &err), DFL_E_INPUT, "%s accepted", bad[i]);
    static const char *const good[] = {"o", "../o", "../../o", "a/b", ".o", "..o", "o..", "/tmp/x"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
        cr_expect_eq(dfl_dir_check_name(good[i], "--out", &err), DFL_OK, "%s: %s", good[i], err.msg);
    /* '..' after a missing folder is refused, after an existing one fine */
    snprintf(d, sizeof d, "%s/nonexist/../y", t);
    cr_expect_eq(dfl_dir_check_name(d, "--out", &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "nonexist") != NULL, "%s", err.msg);
    snprintf(d, sizeof d, "%s/../y", t);
    cr_expect_eq(dfl_dir_check_name(d, "--out", &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(tmpdir_count(t), 0, "the check made something");
    tmpdir_remove(t);
}

Test(dirs, replace_swaps_and_leaves_nothing_else)
{
    char t[256], a[512], b[512], p[600];
    tmpdir_new(t, sizeof t);
    snprintf(a, sizeof a, "%s/fresh", t);
    snprintf(b, sizeof b, "%s/out", t);
    dfl_err err;
    mkdir(a, 0755);
    tmpdir_write(a, "one", "1", p, sizeof p);
    cr_assert_eq(dfl_dir_replace(a, b, &err), DFL_OK, "%s", err.msg); /* no dst yet */
    mkdir(a, 0755);
    tmpdir_write(a, "two", "2", p, sizeof p);
    cr_assert_eq(dfl_dir_replace(a, b, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(tmpdir_count(t), 1, "only out/ is left");
    cr_expect_eq(tmpdir_count(b), 1);
    snprintf(p, sizeof p, "%s/two", b);
    cr_expect_eq(access(p, F_OK), 0, "out/ is the new folder");
    tmpdir_remove(t);
}

Test(dirs, restore_stale_puts_back_only_a_dead_runs_lone_backup)
{
    char t[256], out[512], bak[1200], p[1300], host[256];
    tmpdir_new(t, sizeof t);
    snprintf(out, sizeof out, "%s/o", t);
    /* the host part as dfl_dir_owned_name spells it */
    dfl_dir_owned_name("x", "old", host, sizeof host);
    char *h = strchr(host + 6, '\0');
    while (h > host && h[-1] != '.') h--;
    h[-1] = '\0';
    FILE *fp = fopen("/proc/sys/kernel/pid_max", "r");
    long pid_max = 4194304;
    if (fp) {
        cr_assert_eq(fscanf(fp, "%ld", &pid_max), 1);
        fclose(fp);
    }
    snprintf(bak, sizeof bak, "%s/o.old.%s.%ld", t, host + 6, pid_max + 1); /* no such process */
    mkdir(bak, 0755);
    tmpdir_write(bak, "f", "x", p, sizeof p);
    mkdir(out, 0755); /* dst exists: left alone */
    cr_expect(!dfl_dir_restore_stale(bak, out));
    cr_expect_eq(access(bak, F_OK), 0);
    rmdir(out);
    cr_expect(dfl_dir_restore_stale(bak, out), "a dead run's backup of a missing folder");
    snprintf(p, sizeof p, "%s/f", out);
    cr_expect_eq(access(p, F_OK), 0);
    cr_expect_eq(access(bak, F_OK), -1);
    /* this process's own backup: its owner lives */
    dfl_dir_owned_name(out, "old", bak, sizeof bak);
    cr_assert_eq(rename(out, bak), 0);
    cr_expect(!dfl_dir_restore_stale(bak, out));
    cr_expect_eq(access(bak, F_OK), 0);
    tmpdir_remove(t);
}

Test(dirs, probe_leaves_nothing)
{
    char t[256];
    tmpdir_new(t, sizeof t);
    cr_expect_eq(dfl_dir_probe(t), 0);
    cr_expect_eq(tmpdir_count(t), 0);
    cr_expect_neq(dfl_dir_probe("/proc"), 0, "/proc takes no files");
    char d[512];
    snprintf(d, sizeof d, "%s/missing", t);
    cr_expect_neq(dfl_dir_probe(d), 0);
    cr_expect_eq(tmpdir_count(t), 0);
    tmpdir_remove(t);
}

/* dfl_path_stamp: every spelling of one file gives one stamp; below a
 * ".git" (folder or a worktree's file) it is relative to that root, the
 * nearest one winning; elsewhere the absolute resolved path. */
Test(dirs, path_stamp_is_one_name_whatever_the_spelling)
{
    char dir[64], p[600], real_dir[PATH_MAX], buf[4096], want[PATH_MAX + 64];
    dfl_err err;
    tmpdir_new(dir, sizeof dir);
    cr_assert_not_null(realpath(dir, real_dir));
    tmpdir_write(dir, "repo/configs/paper/x.ini", "[study]\n", p, sizeof p);
    tmpdir_write(dir, "plain/y.ini", "[study]\n", p, sizeof p);
    snprintf(p, sizeof p, "%s/repo/.git", dir);
    cr_assert_eq(mkdir(p, 0755), 0);
    snprintf(p, sizeof p, "%s/link", dir);
    cr_assert_eq(symlink("repo/configs", p), 0);
    const char *spell[] = {"%s/repo/configs/paper/x.ini", "%s/repo/configs/../configs/paper/x.ini",
                           "%s//repo/./configs/paper//x.ini", "%s/link/paper/x.ini"};
    for (size_t i = 0; i < sizeof spell / sizeof spell[0]; i++) {
        char path[700];
        snprintf(path, sizeof path, spell[i], dir);
        dfl_err_clear(&err);
        cr_assert_eq(dfl_path_stamp(path, buf, sizeof buf, &err), DFL_OK, "%s: %s", path, err.msg);
        cr_expect_str_eq(buf, "configs/paper/x.ini", "spelling %s", path);
    }
    /* from inside the repository, a relative spelling */
    char cwd[PATH_MAX];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    snprintf(p, sizeof p, "%s/repo/configs", dir);
    cr_assert_eq(chdir(p), 0);
    dfl_status st = dfl_path_stamp("./paper/../paper/x.ini", buf, sizeof buf, &err);
    cr_assert_eq(chdir(cwd), 0);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    cr_expect_str_eq(buf, "configs/paper/x.ini");
    /* a nearer root wins: a worktree's ".git" is a file */
    snprintf(p, sizeof p, "%s/repo/configs/paper/.git", dir);
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f);
    fputs("gitdir: elsewhere\n", f);
    fclose(f);
    snprintf(p, sizeof p, "%s/repo/configs/paper/x.ini", dir);
    cr_assert_eq(dfl_path_stamp(p, buf, sizeof buf, &err), DFL_OK, "%s", err.msg);
    cr_expect_str_eq(buf, "x.ini");
    /* no repository above: the absolute resolved path */
    snprintf(p, sizeof p, "%s/plain/../plain/y.ini", dir);
    cr_assert_eq(dfl_path_stamp(p, buf, sizeof buf, &err), DFL_OK, "%s", err.msg);
    snprintf(want, sizeof want, "%s/plain/y.ini", real_dir);
    cr_expect_str_eq(buf, want);
    /* too long for buf; a missing file */
    cr_expect_eq(dfl_path_stamp(p, buf, strlen(want), &err), DFL_E_INPUT);
    cr_expect_eq(dfl_path_stamp(p, buf, strlen(want) + 1, &err), DFL_OK, "%s", err.msg);
    snprintf(p, sizeof p, "%s/plain/none.ini", dir);
    dfl_err_clear(&err);
    cr_expect_eq(dfl_path_stamp(p, buf, sizeof buf, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "none.ini") != NULL, "%s", err.msg);
    tmpdir_remove(dir);
}
