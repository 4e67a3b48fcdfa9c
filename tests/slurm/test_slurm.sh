#!/usr/bin/env bash
# test_slurm.sh — deploy/slurm's batch scripts on a real one-host Slurm cluster
# (slurmctld, slurmd, munge from Debian; deploy/slurm/test-cluster.sh, started
# by deploy/test.sh, which exports SLURM_CONF). No GPU here: the jobs drop the
# gres with `sbatch --gres=none` and render with llvmpipe.
#
#   1. fluidcastd.sbatch: the address file appears (mode 600: umask 077) with
#      tls://127.0.0.1:PORT and the job's certificate next to it; the real
#      fluidcast client renders through it with the job's token and
#      certificate (and is refused without either, each with its exit status);
#      `scancel` ends it: its log says it drained ("SIGTERM received:
#      stopping", status 0), the job is CANCELLED and the address and
#      certificate files are gone.
#   2. The same script, stopped as --signal=B:TERM@60 does it (`scancel --batch
#      --signal=TERM`: the batch shell only): the script passes SIGTERM on, the
#      daemon drains and the job COMPLETES with exit code 0.
#   3. fluidcastd-ranks.sbatch with 2 ranks: each rank renders through the daemon
#      on its node (the Unix socket in FLUIDCAST_SERVER); the job COMPLETES.
#
# Usage: test_slurm.sh FLUIDCASTD FLUIDCAST SOURCE_DIR. Exit 77 (skip) when no
# test cluster is up, saying how to start one.
set -uo pipefail

daemon=$(realpath "$1") client=$(realpath "$2") source=$(realpath "$3")
skip() { echo "SKIP: $*"; exit 77; }
if [[ -z ${SLURM_CONF:-} ]] || ! command -v sbatch >/dev/null; then
    skip "no Slurm test cluster: deploy/test.sh starts one (deploy/slurm/test-cluster.sh start DIR; export SLURM_CONF=DIR/slurm.conf)"
fi
sinfo -h -o %t 2>/dev/null | grep -q idle || skip "the Slurm cluster of SLURM_CONF=$SLURM_CONF has no idle node"

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
work=$(mktemp -d /tmp/fc-slurm-test-XXXXXX)
jobs_started=()
cleanup() {
    local job
    for job in "${jobs_started[@]}"; do scancel "$job" 2>/dev/null; done
}
trap cleanup EXIT

# The token of jobs 1 and 2, made before they start (two scripts making it at once would race);
# the ranks' job makes its own (fluidcastd-ranks.sbatch), checked below.
(umask 077; head -c 32 /dev/urandom | base64 > "$work/token")

# A ball of particles to render (binary .f32: x y z per particle).
python3 -c "
import math, struct
with open('$work/ball.f32', 'wb') as f:
    for i in range(400):
        t, p = math.acos(1 - 2 * (i + 0.5) / 400), math.pi * (1 + 5 ** 0.5) * i
        f.write(struct.pack('<3f', 0.3 * math.sin(t) * math.cos(p), 0.3 * math.sin(t) * math.sin(p), 0.3 * math.cos(t)))
"

# Runs fluidcastd.sbatch in DIR; prints the job id.
submit_daemon() {
    local dir=$1
    mkdir -p "$dir"
    FLUIDCASTD=$daemon FLUIDCAST_LISTEN_HOST=127.0.0.1 FLUIDCAST_ADDRESS_FILE=$dir/address \
        FLUIDCAST_TOKEN_FILE=$work/token FLUIDCAST_GPU=software \
        sbatch --parsable --gres=none --cpus-per-task=1 --time=10 --chdir="$dir" --output="$dir/job.log" \
        "$source/deploy/slurm/fluidcastd.sbatch"
}

wait_for_file() {   # FILE SECONDS
    local i
    for ((i = 0; i < $2 * 5; i++)); do [[ -s $1 ]] && return 0; sleep 0.2; done
    return 1
}

wait_job_gone() {   # JOB SECONDS
    local i
    for ((i = 0; i < $2 * 5; i++)); do
        [[ -z $(squeue -h -j "$1" 2>/dev/null) ]] && return 0
        sleep 0.2
    done
    return 1
}

job_state() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z]*\).*/\1/p'; }
job_exit() { scontrol show job "$1" | sed -n 's/.* ExitCode=\([0-9:]*\).*/\1/p'; }

check_drained() {   # DIR WHAT
    grep -q "SIGTERM received: stopping" "$1/job.log" || fail "$2: the daemon's log has no drain ('SIGTERM received: stopping')"
    grep -q "fluidcastd exited with status 0" "$1/job.log" || fail "$2: the daemon did not exit 0"
    [[ ! -e $1/address ]] || fail "$2: the address file outlived the daemon"
    [[ ! -e $1/address.pem ]] || fail "$2: the certificate file outlived the daemon"
}

grep -q '^#SBATCH --signal=B:TERM@60$' "$source/deploy/slurm/fluidcastd.sbatch" || fail "fluidcastd.sbatch lacks --signal=B:TERM@60"
grep -q '^#SBATCH --gres=gpu:1$' "$source/deploy/slurm/fluidcastd.sbatch" || fail "fluidcastd.sbatch asks for no GPU"

# 1 and 2 run side by side (one CPU each).
one=$(submit_daemon "$work/one") && jobs_started+=("$one") || { fail "fluidcastd.sbatch was not accepted"; one=none; }
two=$(submit_daemon "$work/two") && jobs_started+=("$two") || { fail "fluidcastd.sbatch was not accepted"; two=none; }
echo "jobs $one (scancel) and $two (--signal=B:TERM) submitted"

if wait_for_file "$work/one/address" 120; then
    address=$(cat "$work/one/address")
    [[ $address =~ ^tls://127\.0\.0\.1:[0-9]+$ ]] || fail "address file holds '$address'"
    [[ $(stat -c %a "$work/one/address") == 600 ]] || fail "address file mode $(stat -c %a "$work/one/address"), not 600"
    [[ -s $work/one/address.pem ]] || fail "the job handed back no certificate (address.pem)"
    out=$("$client" snapshot "$work/ball.f32" -o "$work/one.png" --size 64x48 --server "$address" \
        --tls-ca "$work/one/address.pem" --token-file "$work/token" 2>&1) || fail "render through $address: $out"
    [[ $out == *"64x48 PNG"* ]] || fail "render said: $out"
    [[ $(head -c 8 "$work/one.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "one.png is no PNG"
    "$client" info --server "$address" --tls-ca "$work/one/address.pem" > "$work/no-token.txt" 2>&1
    status=$?
    [[ $status -eq 5 ]] || fail "without the token: exit $status, expected 5 (refused): $(cat "$work/no-token.txt")"
    "$client" info --server "$address" --token-file "$work/token" > "$work/no-ca.txt" 2>&1
    status=$?
    [[ $status -eq 8 ]] || fail "without the job's certificate: exit $status, expected 8 (unknown CA): $(cat "$work/no-ca.txt")"
    echo "job $one: rendered through $address"
else
    fail "job $one never wrote its address: $(cat "$work/one/job.log" 2>/dev/null)"
fi
scancel "$one"
wait_job_gone "$one" 60 || fail "job $one still queued 60 s after scancel"
check_drained "$work/one" "scancel"
[[ $(job_state "$one") == CANCELLED ]] || fail "job $one: state $(job_state "$one") after scancel"

if wait_for_file "$work/two/address" 120; then
    scancel --batch --signal=TERM "$two"
    wait_job_gone "$two" 60 || fail "job $two still queued 60 s after SIGTERM to its batch shell"
    check_drained "$work/two" "--signal=B:TERM"
    [[ $(job_state "$two") == COMPLETED && $(job_exit "$two") == 0:0 ]] ||
        fail "job $two: state $(job_state "$two"), exit $(job_exit "$two") after SIGTERM to the batch shell"
else
    fail "job $two never wrote its address: $(cat "$work/two/job.log" 2>/dev/null)"
fi

# 3: two ranks, each renders through its node's daemon; rank 0 also reaches the node's daemon over its TCP
# address for viewers, in TLS with the node's certificate.
mkdir -p "$work/ranks"
cat > "$work/ranks/rank.sh" <<RANK
#!/bin/bash
if [[ \$SLURM_PROCID == 0 ]]; then
    address=\$(cat "$work/ranks/addresses/"*.address)
    echo "\$address" > "$work/ranks/tcp_address.txt"
    "$client" info --server "\$address" --tls-ca "\$(ls "$work/ranks/addresses/"*.address.pem)" \\
        --token-file "\$FLUIDCAST_TOKEN_FILE" > "$work/ranks/info.txt" || exit 1
fi
exec "$client" snapshot "$work/ball.f32" -o "$work/ranks/rank-\$SLURM_PROCID.png" --size 40x40 \\
    --server "\$FLUIDCAST_SERVER" --token-file "\$FLUIDCAST_TOKEN_FILE"
RANK
chmod +x "$work/ranks/rank.sh"
ranks=$(FLUIDCASTD=$daemon FLUIDCAST_LISTEN_HOST=127.0.0.1 FLUIDCAST_ADVERTISE_HOST=127.0.0.1 \
    FLUIDCAST_ADDRESS_DIR=$work/ranks/addresses FLUIDCAST_TOKEN_FILE=$work/ranks/token FLUIDCAST_GPU=software \
    FLUIDCAST_SOCKET=$work/ranks/fluidcast.sock \
    sbatch --parsable --gres=none --nodes=1 --ntasks=2 --ntasks-per-node=2 --time=10 --chdir="$work/ranks" \
    --output="$work/ranks/job.log" "$source/deploy/slurm/fluidcastd-ranks.sbatch" "$work/ranks/rank.sh") &&
    jobs_started+=("$ranks")
[[ -n $ranks ]] || { fail "fluidcastd-ranks.sbatch was not accepted"; ranks=none; }
echo "job $ranks: 2 ranks"
wait_job_gone "$ranks" 180 || fail "job $ranks still running after 180 s"
[[ $(job_state "$ranks") == COMPLETED && $(job_exit "$ranks") == 0:0 ]] ||
    fail "job $ranks: state $(job_state "$ranks"), exit $(job_exit "$ranks"): $(grep -v ' info ' "$work/ranks/job.log")"
for r in 0 1; do
    [[ -s $work/ranks/rank-$r.png ]] || fail "rank $r wrote no image"
done
[[ $(stat -c %a "$work/ranks/token" 2>/dev/null) == 600 ]] || fail "the token the ranks' job made is not mode 600"
[[ $(grep -c "unix#[0-9]*: HELLO from 'fluidcast snapshot'" "$work/ranks/job.log") -eq 2 ]] ||
    fail "the node's daemon did not serve both ranks over its Unix socket"
grep -q "fluidcastd on .* exited with status 0" "$work/ranks/job.log" || fail "the ranks' daemon did not drain and exit 0"
[[ $(cat "$work/ranks/tcp_address.txt" 2>/dev/null) == tls://127.0.0.1:* ]] ||
    fail "the node's address for viewers is not tls://: $(cat "$work/ranks/tcp_address.txt" 2>/dev/null)"
[[ -s $work/ranks/info.txt ]] || fail "fluidcast info over TLS with the node's certificate failed"
[[ ! -e $work/ranks/addresses/$(hostname -s).address.pem ]] || fail "the node's certificate was left behind"

if [[ $failures -eq 0 ]]; then
    rm -rf "$work"
    echo "slurm: all checks passed"
    exit 0
fi
echo "slurm: $failures check(s) failed; files in $work"
exit 1
