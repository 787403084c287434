#!/bin/bash
# The output-folder cases of `dflab run` and `dflab merge`, run under one
# watched parent folder W: a listing of W (every path, type, mode and
# sha256) taken before and after each refused case must be identical, and
# after a case that writes, only OUT and OUT.points may differ.
# usage: outdir_cases.sh DFLAB DIR   (DIR empty; prints "ok" at the end)
set -u
DFLAB=$1
W=$2
cd "$W" || exit 1
die() { echo "FAIL: $*"; exit 1; }
mkdir w && cd w || exit 1
P=$W/w
printf '[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n[field]\nkind = exact\n[grid]\nn = 8, 12\n' > g.ini
cp g.ini ...ini
cp g.ini ..ini
# the listing of P, leaving out the paths under the given folders
listing() {
    local skip=()
    for x in "$@"; do skip+=(-path "$P/$x" -prune -o -path "$P/$x.points" -prune -o); done
    find "$P" "${skip[@]}" -printf '%P %y %m\n' | LC_ALL=C sort
    find "$P" "${skip[@]}" -type f -print0 | LC_ALL=C sort -z | xargs -0 -r sha256sum
}
# refused CASE ARGS...: exit 2, one error line holding WANT, P unchanged
refused() {
    local want=$1
    shift
    listing > ../before
    "$DFLAB" "$@" > ../out 2> ../err
    local rc=$?
    listing > ../after
    [ $rc = 2 ] || die "$*: exit $rc: $(cat ../err)"
    [ "$(grep -c '^dflab: error: ' ../err)" = 1 ] && grep -qF -- "$want" ../err \
        || die "$*: message lacks '$want': $(cat ../err)"
    diff ../before ../after > ../diff || die "$*: the parent folder changed: $(cat ../diff)"
}
# wrote OUT ARGS...: exit 0, nothing but OUT and OUT.points changed
wrote() {
    local out=$1
    shift
    listing "$out" > ../before
    "$DFLAB" "$@" > ../out 2> ../err || die "$*: failed: $(cat ../err)"
    listing "$out" > ../after
    diff ../before ../after > ../diff || die "$*: wrote outside $out: $(cat ../diff)"
}

wrote o run g.ini --out o --quiet
[ -f o/manifest.json ] && head -3 o/manifest.json | grep -q '"format": "dflab-results"' \
    || die "the manifest lacks the format magic"

# someone else's folder with a manifest.json: never replaced
mkdir -p webapp/src
echo '{"name": "webapp"}' > webapp/manifest.json
echo '<html>' > webapp/index.html
echo 'x' > webapp/src/app.js
refused "--out webapp: manifest.json is not a dflab results manifest" run g.ini --out webapp --quiet
refused "merge webapp: manifest.json is not a dflab" merge webapp
# no manifest at all: the first entry is named
refused "--out webapp/src: exists and is not a dflab results folder (no manifest.json; it holds app.js)" \
    run g.ini --out webapp/src --quiet
# a dflab folder with a file added, a sub-folder added, a newer format
cp -r o o2 && cp -r o.points o2.points
echo notes > o2/notes.txt
refused "--out o2: holds notes.txt, which its manifest.json does not list" run g.ini --out o2 --quiet --force
refused "merge o2: holds notes.txt" merge o2
rm o2/notes.txt && mkdir o2/config.ini.d
refused "holds config.ini.d" run g.ini --out o2 --quiet
rmdir o2/config.ini.d
sed -i 's/"format_version": 1,/"format_version": 2,/' o2/manifest.json
refused "--out o2: manifest.json is not a dflab results manifest" run g.ini --out o2 --quiet
# a manifest naming a file the folder holds as a directory
rm -rf o2 o2.points

# names that are not new folders
refused "--out .: a results folder cannot be named" run g.ini --out . --quiet
refused "--out ..: a results folder cannot be named" run g.ini --out .. --quiet
refused "--out res/.: a results folder cannot be named" run g.ini --out res/. --quiet
refused "--out o/..: a results folder cannot be named" run g.ini --out o/.. --quiet
refused "--out nonexist/../y: '..' follows nonexist" run g.ini --out nonexist/../y --quiet
refused "...ini: the config's name '..' cannot name its results folder" run ...ini --quiet
refused "..ini: the config's name '.' cannot name its results folder" run ..ini --quiet
refused "...ini: the config's name '..'" run ...ini --set grid.n=8 --quiet
refused "..ini: the config's name '.'" plan ..ini
refused "merge .: a results folder cannot be named" merge .
refused "merge ..: a results folder cannot be named" merge ..

# a folder dflab wrote before the format magic (no "format" lines): replaced
wrote o run g.ini --out o --quiet
sed -i '2,3d' o/manifest.json
wrote o run g.ini --out o --quiet --force
head -3 o/manifest.json | grep -q '"format": "dflab-results"' || die "old-shape folder not replaced"

# a replacement cut off between its two renames (file systems without
# RENAME_EXCHANGE): the dead run's backup is the only copy and comes back
dead=$(( $(cat /proc/sys/kernel/pid_max) + 1 ))
host=$(hostname | tr './' '__')
listing > ../before
mv o "o.old.$host.$dead"
mv o.points keep.points
"$DFLAB" merge o > ../out 2> ../err
rc=$?
mv keep.points o.points
listing > ../after
[ $rc = 2 ] || die "merge without points: exit $rc"
[ -d o ] && [ ! -e "o.old.$host.$dead" ] || die "the backup was not restored: $(ls)"
diff ../before ../after > ../diff || die "restored folder differs: $(cat ../diff)"

# a kill at the swap leaves the old folder whole; with the swap done the
# run completes (strace stops dflab at the rename calls naming o)
if command -v strace > /dev/null; then
    sha() { (cd o && sha256sum $(ls | grep -v manifest.json)) }
    old=$(sha)
    (strace -f -qq -P "$P/o" -e trace=rename,renameat,renameat2 \
        -e inject=rename,renameat,renameat2:signal=SIGKILL:when=1 \
        "$DFLAB" run g.ini --out "$P/o" --quiet --force > /dev/null 2>&1 || true) 2> /dev/null
    [ -d o ] && [ "$(sha)" = "$old" ] || die "a kill at the first rename of o lost the folder: $(ls)"
    ls -d o.stage.* > /dev/null 2>&1 || die "the kill did not land at the swap: $(ls)"
    (strace -f -qq -P "$P/o" -e trace=rename,renameat,renameat2 \
        -e inject=rename,renameat,renameat2:signal=SIGKILL:when=2 \
        "$DFLAB" run g.ini --out "$P/o" --quiet --force > /dev/null 2>&1 || true) 2> /dev/null
    [ -f o/manifest.json ] || die "a kill at a second rename of o left no folder: $(ls)"
    wrote o run g.ini --out o --quiet
    [ -z "$(ls -a | grep -E '\.(stage|old)\.')" ] || die "leftovers after the rerun: $(ls -a)"
    # a file system without RENAME_EXCHANGE (renameat2 made to fail with
    # EINVAL): a kill between the two renames leaves no o/ and the
    # backup, which the next dflab puts back.  Not under the sanitizer build:
    # a preloaded library ahead of the ASan runtime stops the process.
    if command -v cc > /dev/null && [ -z "${DFL_SANITIZE:-}" ]; then
        cat > ../noexchange.c <<'EOF'
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdarg.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
long syscall(long n, ...)
{
    va_list ap;
    va_start(ap, n);
    long a[6];
    for (int i = 0; i < 6; i++) a[i] = va_arg(ap, long);
    va_end(ap);
    if (n == SYS_renameat2) {
        errno = EINVAL;
        return -1;
    }
    long (*real)(long, ...) = (long (*)(long, ...))dlsym(RTLD_NEXT, "syscall");
    return real(n, a[0], a[1], a[2], a[3], a[4], a[5]);
}
/* SIGKILL right after a rename to a name that starts with $KILL_AFTER_ASIDE */
int rename(const char *from, const char *to)
{
    int (*real)(const char *, const char *) =
        (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    const int r = real(from, to);
    const char *k = getenv("KILL_AFTER_ASIDE");
    if (r == 0 && k && strncmp(to, k, strlen(k)) == 0) raise(SIGKILL);
    return r;
}
EOF
        cc -shared -fPIC -o ../noexchange.so ../noexchange.c -ldl || die "shim does not build"
        old=$(sha)
        (KILL_AFTER_ASIDE="$P/o.old." LD_PRELOAD="$W/noexchange.so" \
            "$DFLAB" run g.ini --out "$P/o" --quiet --force > /dev/null 2>&1 || true) 2> /dev/null
        [ ! -e o ] && ls -d o.old.* > /dev/null 2>&1 || die "the kill did not land between the renames: $(ls)"
        mv o.points keep.points
        LD_PRELOAD="$W/noexchange.so" "$DFLAB" merge o > /dev/null 2>&1
        mv keep.points o.points
        [ -d o ] && [ "$(sha)" = "$old" ] && ! ls -d o.old.* > /dev/null 2>&1 \
            || die "the backup of a cut-off replacement was not put back: $(ls)"
        LD_PRELOAD="$W/noexchange.so" "$DFLAB" run g.ini --out o --quiet --force \
            || die "the two-rename replacement failed"
        [ -z "$(ls -a | grep -E '\.(stage|old)\.')" ] || die "leftovers after the two renames: $(ls -a)"
    fi
else
    echo "strace missing: the kill at the swap is not checked"
fi

# no probe or stage of any run is left in the parent
[ -z "$(find "$P" -name '.dflab*probe*')" ] || die "probe left: $(find "$P" -name '.dflab*probe*')"
echo ok
