#!/bin/bash
# End-to-end sweeps: one 24-point sweep of the bs04_gradbounds paper config
# (shrunk with --set) run as one process, under GNU parallel with a killed
# job resumed, as a Slurm array on a private single-node cluster, and
# killed with SIGKILL midway; each merged result must equal the one-process
# run byte for byte (CSV) and give the same report.  Also: the stale-file
# scenario, merge refusals, provenance.
#
#   tests/e2e/sweeps/sweeps.sh DFLAB WORKDIR CASE
#   CASE: parallel | slurm | sigkill | stale | merge_refusals | provenance
#         | verify (committed points checked against their point.json)
#         | bad_records (malformed point.json, non-regular entries)
# Run from the repository root.  Prints what differs; exit 0 when all holds.
set -euo pipefail
DFLAB=$1
W=$2
CASE=$3
PY=${DFL_PYTHON:-/usr/bin/python3}
CFG=$PWD/configs/paper/bs04/bs04_gradbounds.ini
# 4 alpha x 2 p x 3 parts = 24 points; profiles at alpha 60 and 180
SETS=(--set study.alpha=10,60,90,180 --set study.p=2,7 --set study.join=requiv
      --set study.parts=exact,disk,strip --set study.samples=360
      --set study.profile_samples=36 --set study.fig5_nphi=5)

die() { echo "FAIL: $*" >&2; exit 1; }

# The one-process run spells the config relatively and roundabout, the
# launchers absolutely: provenance (config.ini, point.json, VTK/EXR field
# data) must not depend on the spelling (dfl_path_stamp).
CFG_REL=./configs/../configs/paper/bs04/bs04_gradbounds.ini
one_process() { # DIR [extra args]
    local out=$1; shift
    "$DFLAB" run "$CFG_REL" "${SETS[@]}" --out "$out" --quiet "$@"
}

# The CSVs of two results folders: the same names, the same bytes.
same_csvs() {
    local a=$1 b=$2
    diff <(cd "$a" && ls -- *.csv) <(cd "$b" && ls -- *.csv) >&2 || die "CSV names differ: $a $b"
    for f in "$a"/*.csv; do
        cmp -s "$f" "$b/$(basename "$f")" || die "$(basename "$f") differs between $a and $b"
    done
}

# The report of a folder (as make reproduce writes it), without wall times.
report_of() {
    local res=$1 name=$2
    rm -rf "$W/rep_$name" && mkdir -p "$W/rep_$name"
    cp -r "$res" "$W/rep_$name/bs04_gradbounds"
    cp -r results/reference "$W/rep_$name/reference"
    "$PY" scripts/report.py --results "$W/rep_$name" --out "$W/rep_$name/REPORT.md" >/dev/null
    grep -v '^Wall time' "$W/rep_$name/REPORT.md"
}

same_report() {
    diff <(report_of "$1" a) <(report_of "$2" b) >&2 || die "reports of $1 and $2 differ"
}

points_in() { ls "$1.points" 2>/dev/null | grep -c '^pt[0-9]*$' || true; }

case $CASE in
parallel)
    one_process "$W/one"
    # the plan's GNU parallel line, with a wrapper that SIGKILLs point 5's
    # first attempt midway.  That attempt is made slow (a larger, unswept
    # sample count: ~6 s on one core) so that the kill always lands before
    # it could commit, however fast the machine; a kill that finds the
    # process gone fails the wrapper loudly rather than passing by luck.
    cat > "$W/wrap.sh" <<WRAP
#!/bin/bash
if [[ " \$* " == *" --point 5 "* ]] && [ ! -e "$W/killed" ]; then
    touch "$W/killed"
    "$DFLAB" "\$@" --set study.samples=3600000 & pid=\$!
    sleep 0.3
    kill -9 \$pid || { echo "wrap: point 5 ended before the kill" >&2; touch "$W/kill_missed"; }
    wait \$pid
    exit \$?
fi
exec "$DFLAB" "\$@"
WRAP
    chmod +x "$W/wrap.sh"
    "$DFLAB" plan "$CFG" "${SETS[@]}" --out "$W/par" --emit parallel -j 2 > "$W/line.sh"
    grep -q -- '--joblog' "$W/line.sh" && grep -q -- '--resume-failed' "$W/line.sh" \
        || die "parallel line lacks --joblog/--resume-failed: $(cat "$W/line.sh")"
    sed -i "s|DFLAB_EXE=$DFLAB |DFLAB_EXE=$W/wrap.sh |" "$W/line.sh"
    grep -q wrap.sh "$W/line.sh" || die "wrapper not in line: $(cat "$W/line.sh")"
    if bash "$W/line.sh" 2> "$W/first.err"; then die "the killed job did not fail the line"; fi
    [ -e "$W/killed" ] || die "point 5 was never started"
    [ ! -e "$W/kill_missed" ] || die "point 5 ended before the wrapper's kill: $(cat "$W/first.err")"
    [ ! -e "$W/par" ] || die "a failed parallel run left a merged folder"
    [ "$(points_in "$W/par")" = 23 ] || die "expected 23 committed points, got $(points_in "$W/par")"
    bash "$W/line.sh" 2> "$W/second.err" || die "resumed line failed: $(cat "$W/second.err")"
    # --resume-failed reran only the failed job
    [ "$(grep -c . "$W/par.points/parallel.joblog")" = 26 ] \
        || die "joblog: $(cat "$W/par.points/parallel.joblog")"
    same_csvs "$W/one" "$W/par"
    same_report "$W/one" "$W/par"
    "$PY" scripts/compare_results.py "$W/one" "$W/par" --all >&2 \
        || die "merged and one-process folders differ beyond their manifests"
    ;;
slurm)
    cl=$W/cluster
    trap 'tests/slurm/cluster.sh stop "$cl"' EXIT
    one_process "$W/one"
    # 24 points in batches of 5: 5 tasks (the last one of 4 points)
    "$DFLAB" plan "$CFG" "${SETS[@]}" --out "$W/sl" --emit slurm -j 4 --points-per-task 5 \
        > "$W/sweep.sbatch"
    grep -qx '#SBATCH --array=0-4%4' "$W/sweep.sbatch" || die "no array line: $(head -16 "$W/sweep.sbatch")"
    grep -q '^#SBATCH --mem=[0-9]*M$' "$W/sweep.sbatch" || die "no --mem line"
    grep -q '^#SBATCH --time=[0-9]*$' "$W/sweep.sbatch" || die "no --time line"
    bash -n "$W/sweep.sbatch" || die "script does not parse"
    if ! env_line=$(tests/slurm/cluster.sh start "$cl" 2> "$W/cluster.err"); then
        echo "SLURM-UNAVAILABLE: $(cat "$W/cluster.err")"
        exit 0
    fi
    eval "$env_line"
    sbatch --test-only "$W/sweep.sbatch" 2>&1 | grep -q 'to start' || die "sbatch --test-only rejects the script"
    bash "$W/sweep.sbatch" > "$W/jobs.txt" || die "submission failed"
    for _ in $(seq 600); do
        [ -z "$(squeue -h 2>/dev/null)" ] && break
        sleep 0.2
    done
    [ -z "$(squeue -h)" ] || die "jobs still queued after 120 s: $(squeue)"
    [ "$(ls "$W/sl.logs" | grep -c '^task_[0-9]*\.log$')" = 5 ] || die "logs: $(ls "$W/sl.logs")"
    [ -e "$W/sl/manifest.json" ] || die "merge job did not run: $(cat "$W/sl.logs/merge.log" 2>&1)"
    same_csvs "$W/one" "$W/sl"
    same_report "$W/one" "$W/sl"
    echo "slurm: 24 points in 5 array tasks and the merge ran on $(hostname)"
    ;;
sigkill)
    big=(--set study.samples=36000)
    one_process "$W/ref" "${big[@]}"
    "$DFLAB" run "$CFG" "${SETS[@]}" "${big[@]}" --out "$W/k" --quiet & pid=$!
    for _ in $(seq 2000); do
        [ "$(points_in "$W/k")" -ge 6 ] && break
        kill -0 $pid 2>/dev/null || break
        sleep 0.005
    done
    kill -9 $pid 2>/dev/null || die "the run ended before it could be killed"
    wait $pid || true
    n=$(points_in "$W/k")
    [ "$n" -ge 6 ] && [ "$n" -lt 24 ] || die "expected a partial sweep, got $n points"
    [ ! -e "$W/k" ] || die "a killed run left a merged folder"
    "$DFLAB" run "$CFG" "${SETS[@]}" "${big[@]}" --out "$W/k" 2> "$W/resume.err"
    grep -q "$n of 24 points up to date" "$W/resume.err" || die "resume did not skip: $(cat "$W/resume.err")"
    ls "$W/k.points" | grep -q stage && die "stage folders left: $(ls "$W/k.points")"
    ls "$W" | grep -q '\.stage\.' && die "stage folders left in $W"
    same_csvs "$W/ref" "$W/k"
    ;;
stale)
    # a 24-point custom sweep writes profile_pt001.csv ... (alpha 60, 180)
    one_process "$W/res"
    ls "$W/res" | grep -q '^profile_pt' || die "the custom sweep wrote no profiles"
    # then a 4-point run into the same folder: alpha 10 and 30 have no
    # profile; before, profile_pt001.csv of alpha 60 stayed and was drawn
    # as the alpha = 30 panel
    "$DFLAB" run "$CFG" --set study.alpha=10,30 --set study.p=2,7 --set study.join=requiv \
        --set study.parts=exact --set study.samples=360 --set study.fig5_nphi=5 --out "$W/res" --quiet
    ls "$W/res" | grep -q '^profile' && die "stale profiles: $(ls "$W/res")"
    "$PY" - "$W/res" <<'PYEOF' || die "folder and manifest disagree"
import json, os, sys
d = sys.argv[1]
m = json.load(open(os.path.join(d, "manifest.json")))
listed = {f["name"] for f in m["files"]} | {"manifest.json"}
have = set(os.listdir(d))
assert have == listed, (have ^ listed)
assert len(m["points"]) == 4 and all(p["npoints"] == 4 for p in m["points"])
PYEOF
    [ "$(points_in "$W/res")" = 4 ] || die "points of the earlier sweep kept"
    ;;
merge_refusals)
    for k in $(seq 0 23); do "$DFLAB" run "$CFG" "${SETS[@]}" --out "$W/m" --point "$k" --quiet; done
    "$DFLAB" run "$CFG" --set study.alpha=10 --set study.samples=360 --out "$W/other" --quiet
    expect_refusal() { # want...
        if "$DFLAB" merge "$W/m" 2> "$W/merge.err"; then die "merge accepted: $*"; fi
        [ "$(wc -l < "$W/merge.err")" = 1 ] || die "not one line: $(cat "$W/merge.err")"
        for w in "$@"; do grep -qF -- "$w" "$W/merge.err" || die "message lacks '$w': $(cat "$W/merge.err")"; done
        [ ! -e "$W/m" ] || die "a refused merge wrote $W/m"
        ls "$W" | grep -q '\.stage\.' && die "stage left behind"
        return 0
    }
    mv "$W/m.points/pt017" "$W/pt017"
    expect_refusal "1 of 24 sweep points missing: 17" "m.points"
    cp -r "$W/pt003" "$W/m.points/pt017" 2>/dev/null || cp -r "$W/m.points/pt003" "$W/m.points/pt017"
    expect_refusal "pt017: holds point 3"
    rm -rf "$W/m.points/pt017" && cp -r "$W/other.points/pt000" "$W/m.points/pt017"
    expect_refusal "pt017" "another config"
    rm -rf "$W/m.points/pt017" && mv "$W/pt017" "$W/m.points/pt017"
    "$DFLAB" merge "$W/m" --quiet || die "complete merge refused"
    one_process "$W/one"
    same_csvs "$W/one" "$W/m"
    ;;
provenance)
    one_process "$W/p"
    "$PY" - "$W/p" "$CFG" <<'PYEOF' || die "manifest"
import csv, hashlib, json, os, sys
d, cfg = sys.argv[1], sys.argv[2]
m = json.load(open(os.path.join(d, "manifest.json")))
assert m["overrides"][:2] == ["study.alpha=10,60,90,180", "study.p=2,7"], m["overrides"]
assert len(m["points"]) == 24 and [p["index"] for p in m["points"]] == list(range(24))
for k in ("inih", "ceres", "openexr", "zlib", "dflab"):
    assert m["libraries"][k] and m["libraries"][k] != "unknown", m["libraries"]
p = m["points"][7]
assert p["threads"] >= 1 and p["host"] and p["exit_status"] == 0 and p["wall_seconds"] >= 0
assert p["isa"] in ("sse2", "avx2", "avx512"), p["isa"]
assert "--point" not in p["command_line"] and "run" in p["command_line"]
r = p["resolved"]
# axes in file order, the last fastest: point 7 = alpha 60, p 2, parts disk
assert r["study.alpha"] == "60" and r["study.p"] == "2" and r["study.parts"] == "disk", r
# a single-valued --set is no axis
assert p["sweep_values"] == {"study.alpha": "60", "study.p": "2", "study.parts": "disk"}, p

assert len(p["config_sha256"]) == 64 and len(m["binary_sha256"]) == 64
for f in m["files"]:
    h = hashlib.sha256(open(os.path.join(d, f["name"]), "rb").read()).hexdigest()
    assert h == f["sha256"] and os.path.getsize(os.path.join(d, f["name"])) == f["bytes"], f
rows = list(csv.DictReader(open(os.path.join(d, "bs04_gradbounds.csv"))))
assert [int(x["point"]) for x in rows] == [k for k in range(24) for _ in range(2)]
for x in rows:
    assert float(x["study.alpha"]) == float(x["alpha"]) and x["study.parts"] == x["parts"]
prof = list(csv.DictReader(open(os.path.join(d, "profile_pt006.csv"))))
assert prof and all(x["point"] == "6" and x["study.alpha"] == "60" for x in prof)
PYEOF
    # defaults are part of the resolved config: drop a key from the file
    grep -v '^fd_rel' "$CFG" > "$W/nofd.ini"
    "$DFLAB" run "$W/nofd.ini" --set study.alpha=10 --set study.samples=360 --out "$W/nofd" --quiet
    "$PY" -c "
import json, sys
p = json.load(open('$W/nofd/manifest.json'))['points'][0]
assert p['resolved']['study.fd_rel'] == '1e-05' and 'study.fd_rel' in p['defaults'], p
" || die "default not recorded"
    ;;
verify)
    one_process "$W/one"
    one_process "$W/v"
    P=$W/v.points
    T=bs04_gradbounds.csv
    refuses() { # cmd... : exit 2, one error line naming $want
        local rc=0
        timeout 60 "$@" 2> "$W/err" || rc=$?
        [ "$rc" = 2 ] || die "exit $rc, not 2: $* ($(cat "$W/err"))"
        [ "$(grep -c '^dflab: error: ' "$W/err")" = 1 ] || die "not one error line: $(cat "$W/err")"
        grep -qF -- "$want" "$W/err" || die "message lacks '$want': $(cat "$W/err")"
    }
    # a merged file is a copy: editing it in place leaves the point alone
    [ "$(stat -c %h "$W/v/$T")" = 1 ] || die "merged $T has $(stat -c %h "$W/v/$T") links"
    before=$(sha256sum < "$P/pt001/$T")
    printf 'edited\n' >> "$W/v/$T"
    [ "$(sha256sum < "$P/pt001/$T")" = "$before" ] || die "editing the merged $T changed pt001"
    "$DFLAB" merge "$W/v" --quiet || die "merge of untouched points refused"
    same_csvs "$W/one" "$W/v"
    # a number edited in a point's CSV: merge refuses, a rerun recomputes it
    "$PY" -c "
import re, sys; p = sys.argv[1]; t = open(p).read().split('\n')
t[1] = re.sub('[0-9]', lambda m: str((int(m.group()) + 1) % 10), t[1], count=1)
open(p, 'w').write('\n'.join(t))" "$P/pt001/$T" # same size, other bytes
    want="pt001/$T: sha256 differs"; refuses "$DFLAB" merge "$W/v"
    [ -e "$W/v/manifest.json" ] || die "a refused merge removed the folder"
    one_process "$W/v" 2> /dev/null
    same_csvs "$W/one" "$W/v"
    # a deleted and a truncated file: both recomputed, only those
    rm "$P/pt006/profile_pt006.csv"
    want="pt006/profile_pt006.csv: missing"; refuses "$DFLAB" merge "$W/v"
    truncate -s 10 "$P/pt005/$T"
    "$DFLAB" run "$CFG" "${SETS[@]}" --out "$W/v" 2> "$W/run.err" || die "resume failed: $(cat "$W/run.err")"
    grep -q "22 of 24 points up to date" "$W/run.err" || die "not 2 recomputed: $(cat "$W/run.err")"
    grep -q "pt006/profile_pt006.csv: missing.*recomputing point 6" "$W/run.err" || die "no note: $(cat "$W/run.err")"
    grep -q "pt005/$T: 10 bytes.*recomputing point 5" "$W/run.err" || die "no note: $(cat "$W/run.err")"
    same_csvs "$W/one" "$W/v"
    # a file put into a point would be merged: refused by both
    echo x > "$P/pt003/extra.csv"
    want="pt003/extra.csv: not listed in its point.json"; refuses "$DFLAB" merge "$W/v"
    refuses "$DFLAB" run "$CFG" "${SETS[@]}" --out "$W/v" --quiet
    rm "$P/pt003/extra.csv"
    "$DFLAB" merge "$W/v" --quiet || die "merge refused after the clean-up"
    same_csvs "$W/one" "$W/v"
    ;;
bad_records)
    one_process "$W/b"
    P=$W/b.points/pt001
    cp "$P/point.json" "$W/good.json"
    refuses() { # cmd... : exit 2 within the timeout, one error line naming $want
        local rc=0
        timeout 60 "$@" 2> "$W/err" || rc=$?
        [ "$rc" = 2 ] || die "exit $rc, not 2: $* ($(cat "$W/err"))"
        [ "$(grep -c '^dflab: error: ' "$W/err")" = 1 ] || die "not one error line: $(cat "$W/err")"
        grep -qF -- "$want" "$W/err" || die "message lacks '$want': $(cat "$W/err")"
    }
    both() { # the edit already made: merge and resume refuse it alike
        refuses "$DFLAB" merge "$W/b"
        refuses "$DFLAB" run "$CFG" "${SETS[@]}" --out "$W/b" --quiet
        "$PY" -c "import json,sys; json.load(open(sys.argv[1]))" "$W/b/manifest.json" \
            || die "manifest.json no longer JSON after: $want"
    }
    # every byte offset below is found in the file the way a reader counts
    off() { "$PY" -c "import sys; t=open(sys.argv[1],'rb').read(); print(t.index(sys.argv[2].encode()))" "$P/point.json" "$1"; }
    edit() { cp "$W/good.json" "$P/point.json"; "$PY" -c "
import sys; p=sys.argv[1]; t=open(p,'rb').read(); a,b=sys.argv[2].encode(),sys.argv[3].encode()
assert a in t, a; open(p,'wb').write(t.replace(a,b,1))" "$P/point.json" "$1" "$2"; }
    edit '"npoints": 24' '"npoints": 1000000000000000000'
    want="pt001/point.json: byte $(off 1000000000000000000): npoints: expected an integer in 1..100000000"; both
    edit '"npoints": 24' '"npoints": -5'
    want="pt001/point.json: byte $(off '-5'): npoints: expected an integer"; both
    edit '"index": 1,' '"index": 1e300,'
    want="pt001/point.json: byte $(off 1e300): index: expected an integer in 0..23"; both
    edit '"index": 1,' '"index": 1.5,'
    want="byte $(off 1.5): index: expected an integer"; both
    cp "$W/good.json" "$P/point.json"; printf 'junk\n' >> "$P/point.json"
    want="pt001/point.json: byte $(off junk): expected nothing after the object"; both
    edit '"overrides": [' '"overrides": [,'
    want="pt001/point.json: byte $(( $(off '"overrides": [,') + 14 )): expected a JSON value"; both
    edit '"study": "' '"study": "\u00'
    want="pt001/point.json: byte"; both
    # non-regular entries: refused at once, never waited on
    rm "$P/point.json"; mkfifo "$P/point.json"
    want="pt001/point.json: not a regular file (a FIFO)"; both
    rm "$P/point.json"; cp "$W/good.json" "$P/point.json"
    mkdir "$P/sub"
    want="pt001/sub: not a regular file (a folder"; both
    rmdir "$P/sub"; mkfifo "$P/fifo"
    want="pt001/fifo: not a regular file (a FIFO"; both
    rm "$P/fifo"
    "$DFLAB" merge "$W/b" --quiet || die "merge refused after the clean-up"
    ;;
*)
    die "unknown case $CASE"
    ;;
esac
echo "ok: $CASE"
