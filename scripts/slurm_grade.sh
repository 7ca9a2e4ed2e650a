#!/usr/bin/env bash
# Grades a design on a population as a Slurm job array on a single-node cluster brought
# up on THIS machine: one array task per body, each the idempotent
# `tightfit grade DESIGN BODIES --out OUT --body NAME`; then gathers and prints the
# bodies per hour. Not run by CI: it installs slurm-wlm and munge, writes
# /etc/slurm/slurm.conf and starts munged, slurmctld and slurmd (root on Debian bookworm).
#
#   scripts/slurm_grade.sh TIGHTFIT DESIGN BODIES OUT [CPUS_PER_TASK] [-- GRADE_OPTIONS...]
#
# e.g. scripts/slurm_grade.sh build/release/tightfit examples/grading/left_leg.json \
#        examples/grading/bodies_full.json out/grade_slurm 1 -- --max-iterations 10
# Running it again re-submits the array: graded bodies are skipped, killed ones resume.
# The tasks' logs go to OUT.slurm/ (OUT itself holds only tightfit's files).
set -euo pipefail

if [ $# -lt 4 ]; then
  sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
TIGHTFIT="$(readlink -f "$1")"; DESIGN="$(readlink -f "$2")"; BODIES="$(readlink -f "$3")"
OUT="$(readlink -m "$4")"; CPUS="${5:-1}"
shift $(( $# >= 5 ? 5 : 4 ))
[ "${1:-}" = "--" ] && shift
EXTRA=("$@")
[ "$(id -u)" -eq 0 ] || { echo "slurm_grade: run as root (it installs and starts Slurm)" >&2; exit 2; }

# 1. Packages.
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends slurm-wlm munge
fi

# 2. Munge (authentication between the Slurm daemons): a key, and the daemon as user munge.
if [ ! -s /etc/munge/munge.key ]; then
  if command -v mungekey >/dev/null; then mungekey --create --force; else
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none; fi
fi
chown munge:munge /etc/munge/munge.key; chmod 400 /etc/munge/munge.key
mkdir -p /run/munge /var/log/munge /var/lib/munge
chown munge:munge /run/munge /var/log/munge /var/lib/munge
if ! munge -n >/dev/null 2>&1; then runuser -u munge -- /usr/sbin/munged; sleep 1; fi
munge -n | unmunge >/dev/null

# 3. A single-node slurm.conf for this machine: every core, the memory Linux reports.
HOST="$(hostname -s)"
MEM_MB="$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)"
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
cat > /etc/slurm/slurm.conf <<CONF
# Written by tightfit's scripts/slurm_grade.sh: one node, this machine.
ClusterName=tightfit
SlurmctldHost=$HOST
SlurmUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
MaxArraySize=100001
NodeName=$HOST CPUs=$(nproc) RealMemory=$MEM_MB State=UNKNOWN
PartitionName=grade Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
CONF

# 4. The daemons (restarted, so that they read this configuration).
for d in slurmctld slurmd; do
  if [ -s /run/$d.pid ] && kill -0 "$(cat /run/$d.pid)" 2>/dev/null; then kill "$(cat /run/$d.pid)"; sleep 2; fi
done
slurmctld
slurmd
for _ in $(seq 60); do
  state="$(sinfo -h -n "$HOST" -o '%T' 2>/dev/null || true)"
  case "$state" in idle*|mix*|alloc*) break ;; down*|drain*) scontrol update nodename="$HOST" state=resume || true ;; esac
  sleep 1
done
sinfo

# 5. The array: task i grades body i of BODIES.
mapfile -t NAMES < <(python3 -c 'import json,sys; [print(b["name"]) for b in json.load(open(sys.argv[1]))["bodies"]]' "$BODIES")
N="${#NAMES[@]}"
LOGS="$OUT.slurm"
mkdir -p "$LOGS"
printf '%s\n' "${NAMES[@]}" > "$LOGS/bodies.txt"
cat > "$LOGS/task.sh" <<TASK
#!/usr/bin/env bash
NAME="\$(sed -n "\$((SLURM_ARRAY_TASK_ID + 1))p" "$LOGS/bodies.txt")"
START=\$(date +%s.%N)
"$TIGHTFIT" --threads "\$SLURM_CPUS_PER_TASK" grade "$DESIGN" "$BODIES" --out "$OUT" --body "\$NAME" ${EXTRA[*]}
CODE=\$?
echo "\$START \$(date +%s.%N)" > "$LOGS/span-\${SLURM_ARRAY_JOB_ID}_\${SLURM_ARRAY_TASK_ID}.txt"
exit \$CODE
TASK
chmod +x "$LOGS/task.sh"
start=$(date +%s.%N)
job=$(sbatch --parsable --array="0-$((N - 1))" --cpus-per-task="$CPUS" --job-name=tightfit-grade \
        --output="$LOGS/task-%A_%a.log" "$LOGS/task.sh")
# Polled every second (`sbatch --wait` polls at growing intervals: up to half a minute late).
while [ -n "$(squeue -h -j "${job%%;*}" 2>/dev/null)" ]; do sleep 1; done
end=$(date +%s.%N)
echo "slurm_grade: array job ${job%%;*} ended after $(python3 -c "print(round($end - $start, 1))") s"
sacct -j "${job%%;*}" 2>/dev/null || squeue || true

# 6. Gather, and the rate of this array (bodies skipped as graded already do not count).
set +e
"$TIGHTFIT" grade "$DESIGN" "$BODIES" --out "$OUT" --gather
code=$?
set -e
id="${job%%;*}"
graded=$(cat "$LOGS"/task-"${id}"_*.log 2>/dev/null | grep -c "^tightfit grade: body .* done in" || true)
skipped=$(cat "$LOGS"/task-"${id}"_*.log 2>/dev/null | grep -c "graded already" || true)
# Two rates: over the wall time from sbatch to the array's end (with Slurm's scheduling)
# and over the span of the tasks (first start to last end).
span=$(cat "$LOGS"/span-"${id}"_*.txt | awk 'NR == 1 {a = $1; b = $2} {if ($1 < a) a = $1; if ($2 > b) b = $2} END {print b - a}')
python3 -c "import sys; n, k, s, t = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4]); print(f'slurm_grade: this array graded {n} bodies ({k} skipped as graded already): {s:.1f} s wall (sbatch to the end of the array), {n * 3600 / s:.1f} bodies per hour; tasks from first start to last end {t:.1f} s, {n * 3600 / t:.1f} bodies per hour')" \
  "$graded" "$skipped" "$(python3 -c "print($end - $start)")" "$span"
exit $code
