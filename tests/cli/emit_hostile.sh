#!/bin/bash
# The scripts of `dflab plan --emit parallel|slurm` and `--commands`, run
# with hostile file names against stub parallel/sbatch/srun first in PATH.
# The stubs record their arguments (NUL-separated) and do what the real
# launcher would (parallel: join the words, replace {}, run them in a
# shell; Slurm: run the script per array task and the --wrap command in
# sh), so the real dflab computes the sweep.  Checks: no command hidden in
# a name runs (no PWNED file appears anywhere), the stubs and dflab got the
# exact names, and #SBATCH paths Slurm cannot read whole are exit 2.
# usage: emit_hostile.sh DFLAB DIR   (DIR empty; prints "ok" at the end)
set -u
DFLAB=$1
W=$2
cd "$W" || exit 1
die() { echo "FAIL: $*"; exit 1; }
mkdir stubs logs
export STUB_LOG=$W/logs
cat > stubs/sbatch <<'EOF'
#!/bin/bash
n=$(ls "$STUB_LOG" | grep -c '^sbatch\.')
printf '%s\0' "$@" > "$STUB_LOG/sbatch.$n"
echo "100$n"
EOF
cat > stubs/srun <<'EOF'
#!/bin/bash
printf '%s\0' "$@" > "$STUB_LOG/srun"
EOF
# parallel --joblog F --resume-failed -j M WORDS... ::: VALUES...
cat > stubs/parallel <<'EOF'
#!/bin/bash
printf '%s\0' "$@" > "$STUB_LOG/parallel"
[ "$1" = --joblog ] && [ "$3" = --resume-failed ] && [ "$4" = -j ] || exit 99
: > "$2"
shift 5
words=()
while [ "$1" != ::: ]; do words+=("$1"); shift; done
shift
for v in "$@"; do
    cmd="${words[*]}"
    bash -c "${cmd//\{\}/$v}" || exit 1
done
EOF
chmod +x stubs/*
PATH=$W/stubs:$PATH
N=$'x\ntouch PWNED1\n $(touch PWNED2) `touch PWNED3` \'q\' "d" 100% {} a  b'
CFG="$W/c $N.ini"
printf '[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n[field]\nkind = exact\n[grid]\nn = 8, 12\n' > "$CFG"
config_of() { "${DFL_PYTHON:-python3}" -c 'import json,sys; print(json.load(open(sys.argv[1]))["config"], end="")' "$1/manifest.json"; }
args_of() { tr '\0' '\n' < "$1"; }

# ---- GNU parallel: names only in the environment, never in its words
OUT="$W/out $N"
"$DFLAB" plan "$CFG" --emit parallel --set shape.radius=0.25 --out "$OUT" > p.sh || die "plan parallel"
bash -n p.sh || die "parallel line does not parse"
bash p.sh > p.out 2>&1 || die "parallel line failed: $(cat p.out)"
[ -f "$OUT/manifest.json" ] || die "no merged folder at the hostile --out"
[ "$(config_of "$OUT")" = "$CFG" ] || die "dflab got another config name: $(config_of "$OUT")"
mapfile -d '' -t got < logs/parallel
# the default threads per job: this machine's online cores / 4 jobs, at least 1
T=$(( $(getconf _NPROCESSORS_ONLN) / 4 )); [ "$T" -ge 1 ] || T=1
want=(--joblog "$OUT.points/parallel.joblog" --resume-failed -j 4 '"$DFLAB_EXE"' run '"$DFLAB_CONFIG"'
      --set '"$DFLAB_SET_0"' --out '"$DFLAB_OUT"' --threads "$T" --quiet --point '{}' ::: 0 1)
[ "${got[*]}" = "${want[*]}" ] && [ ${#got[@]} = ${#want[@]} ] \
    || die "parallel got: $(args_of logs/parallel)"

# ---- --commands: one shell line per point, then the merge
OUT2="$W/cmd $N"
"$DFLAB" plan "$CFG" --commands --out "$OUT2" > c.sh || die "plan --commands"
bash c.sh > c.out 2>&1 || die "commands failed: $(cat c.out)"
[ -f "$OUT2/manifest.json" ] && [ "$(config_of "$OUT2")" = "$CFG" ] || die "commands: folder or config"

# ---- Slurm: the driver's two sbatch calls, each array task, the merge job
"$DFLAB" plan "$CFG" --emit slurm --out "$W/sl" > s.sbatch || die "plan slurm"
bash -n s.sbatch || die "slurm script does not parse"
grep '^#SBATCH' s.sbatch | grep -v '^#SBATCH [^ ]*$' && die "an #SBATCH line has a blank"
bash s.sbatch > s.out 2>&1 || die "slurm driver failed: $(cat s.out)"
mapfile -d '' -t a0 < logs/sbatch.0
[ "${#a0[@]}" = 2 ] && [ "${a0[0]}" = --parsable ] && [ "${a0[1]}" = s.sbatch ] \
    || die "array submission got: $(args_of logs/sbatch.0)"
mapfile -d '' -t a1 < logs/sbatch.1
[ "${#a1[@]}" = 5 ] && [ "${a1[1]}" = --dependency=afterany:1000 ] \
    && [ "${a1[3]}" = "--output=$W/sl.logs/merge.log" ] || die "merge submission got: $(args_of logs/sbatch.1)"
[[ "${a1[2]}" =~ ^--job-name=dflab-[A-Za-z0-9._-]*-merge$ ]] || die "job name: ${a1[2]}"
for k in 0 1; do
    SLURM_ARRAY_TASK_ID=$k bash s.sbatch > "task$k.out" 2>&1 || die "array task $k: $(cat task$k.out)"
done
sh -c "${a1[4]#--wrap=}" > m.out 2>&1 || die "merge job: $(cat m.out)"
[ -f "$W/sl/manifest.json" ] && [ "$(config_of "$W/sl")" = "$CFG" ] || die "slurm: folder or config"
[ ! -e logs/srun ] || die "srun was called"

# ---- #SBATCH paths Slurm cannot read whole: exit 2, nothing on stdout
for bad in $'nl\nx' 'sp ace' 'pc%j' 'bs\x' 'qu"o' "ap'o" 'ha#sh' $'ta\tb'; do
    "$DFLAB" plan "$CFG" --emit slurm --out "$W/$bad" > r.out 2> r.err
    rc=$?
    [ $rc = 2 ] && [ ! -s r.out ] && grep -q '^dflab: error: --out' r.err \
        || die "--out '$bad': exit $rc, stdout $(wc -c < r.out) bytes: $(cat r.err)"
done

leak=$(find "$W" -name 'PWNED*')
[ -z "$leak" ] || die "a command hidden in a name ran: $leak"
echo ok
