#!/usr/bin/env bash
# slurm_local.sh - private single-node Slurm cluster (slurm-wlm 22.05 + munge 0.5.x)
# whose every file lives under one scratch directory: the test that runs the error-against-time
# sweep as a real job array (tests/cli/evt_slurm.sh) starts one on localhost, and docs/results.md
# shows how to try the job-array lines with it. DIR must be a directory (not a link) owned by
# root and writable by root only.
#
#   slurm_local.sh start DIR    # start munged, slurmctld, slurmd; wait for node idle
#   slurm_local.sh stop  DIR    # cancel jobs, stop slurmd, slurmctld, munged
#
# After start:  export SLURM_CONF=DIR/slurm.conf   (or: . DIR/env.sh)
# Can also be sourced; then call slurm_local_start DIR / slurm_local_stop DIR.
#
# Env knobs: SLURM_LOCAL_PORT_BASE (default 16817; ctld=base, slurmd=base+1,
#            next free pair is taken if busy), SLURM_LOCAL_START_TIMEOUT (30 s).
# Must run as root (SlurmUser=root, SlurmdUser=root). Touches nothing outside DIR.

_sl_log() { printf 'slurm_local: %s\n' "$*" >&2; }
_sl_die() { _sl_log "ERROR: $*"; return 1; }

# absolute path of DIR (created if needed); refused when it is a symbolic link, not owned by
# root or writable by group or others (root daemons read their configuration from it)
_sl_absdir() {
    [ -n "$1" ] || { _sl_die "usage: start|stop DIR"; return 1; }
    [ -L "$1" ] && { _sl_die "$1 is a symbolic link: give a directory (e.g. D=\$(mktemp -d))"; return 1; }
    mkdir -p -- "$1" || return 1
    local owner mode
    owner=$(stat -c %u -- "$1") mode=$(stat -c %a -- "$1")
    if [ "$owner" != 0 ] || [ $((0$mode & 022)) -ne 0 ]; then
        _sl_die "$1 must be owned by root and writable by root only (owner uid $owner, mode $mode)"
        return 1
    fi
    (cd -- "$1" && pwd -P)
}

# pid from the pid file $1 if that process is alive and is the daemon $2 (not a reused pid)
_sl_alive_pid() {
    local f=$1 want=${2:-} p
    [ -s "$f" ] || return 1
    p=$(tr -dc '0-9' <"$f")
    [ -n "$p" ] && kill -0 "$p" 2>/dev/null || return 1
    [ -z "$want" ] || [ "$(cat "/proc/$p/comm" 2>/dev/null)" = "$want" ] || return 1
    echo "$p"
}

_sl_port_busy() {
    local p=$1
    if command -v ss >/dev/null 2>&1; then
        # only listeners matter; TIME-WAIT leftovers of a previous run do not block bind
        [ -n "$(ss -Hltn "( sport = :$p )" 2>/dev/null)" ]
    else
        (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null
    fi
}

# failure during start: tear down what was started FIRST (so a closed stderr
# pipe cannot leave daemons behind), then explain and show the log tails.
_sl_fail() {
    local D=$1 msg=$2 extra=${3:-}
    slurm_local_stop "$D" >/dev/null 2>&1
    _sl_log "ERROR: $msg"
    [ -n "$extra" ] && printf '%s\n' "$extra" | sed 's/^/  /' >&2
    _sl_tails "$D"
    return 1
}

_sl_tails() {
    local d=$1 f
    for f in "$d"/log/munged.log "$d"/log/slurmctld.log "$d"/log/slurmd.log; do
        [ -e "$f" ] || continue
        printf '==== tail %s ====\n' "$f" >&2
        tail -n 25 "$f" >&2
    done
}

slurm_local_start() {
    local D
    D=$(_sl_absdir "$1") || return 1
    local conf=$D/slurm.conf sock=$D/munge.sock key=$D/munge.key
    local timeout=${SLURM_LOCAL_START_TIMEOUT:-30}
    local host p cport dport nodeline i st t0

    [ "$(id -u)" = 0 ] || { _sl_die "must run as root"; return 1; }
    for p in munged mungekey munge unmunge slurmctld slurmd sinfo scontrol squeue scancel timeout; do
        command -v "$p" >/dev/null 2>&1 || { _sl_die "$p not found in PATH"; return 1; }
    done
    for p in munged slurmctld slurmd; do
        if _sl_alive_pid "$D/run/$p.pid" "$p" >/dev/null; then
            _sl_die "$p already running for $D (pid $(cat "$D/run/$p.pid")); run stop first"
            return 1
        fi
    done
    t0=$(date +%s.%N)

    # munged requires every directory above its socket to be o+x, and refuses
    # group/other-writable dirs; keep DIR 0755, the key 0600.
    chmod 0755 "$D" || return 1
    mkdir -p "$D/run" "$D/log" "$D/state" "$D/spool" || return 1
    chmod 0755 "$D/run" "$D/log" "$D/spool"
    chmod 0700 "$D/state"

    # ---- munge ----
    if [ ! -s "$key" ]; then
        mungekey --create --keyfile="$key" --bits=1024 || { _sl_die "mungekey failed"; return 1; }
    fi
    chmod 0600 "$key"
    rm -f "$sock" "$sock.lock"
    # --force: munged would refuse a folder above DIR that is 0700 (Debian's /root) or group
    # writable; DIR itself is checked above
    munged --force --socket="$sock" --key-file="$key" --pid-file="$D/run/munged.pid" \
           --log-file="$D/log/munged.log" --seed-file="$D/munged.seed" \
        || { _sl_fail "$D" "munged failed to start"; return 1; }
    if ! munge -n -S "$sock" | unmunge -S "$sock" >/dev/null 2>&1; then
        _sl_fail "$D" "munge round-trip through $sock failed"; return 1
    fi

    # ---- ports: first free consecutive pair from the base ----
    cport=${SLURM_LOCAL_PORT_BASE:-16817}
    for i in $(seq 0 49); do
        if ! _sl_port_busy "$cport" && ! _sl_port_busy $((cport + 1)); then break; fi
        cport=$((cport + 2))
        [ "$i" = 49 ] && { _sl_fail "$D" "no free port pair found"; return 1; }
    done
    dport=$((cport + 1))

    # ---- slurm.conf (regenerated on every start) ----
    host=$(hostname -s)
    # e.g. "NodeName=vm CPUs=2 Boards=1 SocketsPerBoard=1 CoresPerSocket=2 ThreadsPerCore=1 RealMemory=24105"
    nodeline=$(slurmd -C 2>/dev/null | grep -m1 '^NodeName=')
    [ -n "$nodeline" ] || nodeline="NodeName=$host CPUs=$(nproc)"
    nodeline="NodeName=$host ${nodeline#NodeName=* }"

    cat >"$conf" <<EOF
# generated by slurm_local.sh for $D
ClusterName=slurmlocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$cport
SlurmdPort=$dport
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/run/slurmctld.pid
SlurmdPidFile=$D/run/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# default batch_sched_delay=3 adds ~3 s per scheduling wave; 0 -> ~1 s
SchedulerParameters=batch_sched_delay=0
MpiDefault=none
ReturnToService=2
SwitchType=switch/none
MailProg=/bin/true
PlugStackConfig=$D/plugstack.conf
$nodeline NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
    : >"$D/plugstack.conf"
    printf 'export SLURM_CONF=%s\n' "$conf" >"$D/env.sh"

    # ---- daemons (they daemonize themselves and write their pid files) ----
    SLURM_CONF=$conf slurmctld -f "$conf" \
        || { _sl_fail "$D" "slurmctld failed to start"; return 1; }
    SLURM_CONF=$conf slurmd -f "$conf" \
        || { _sl_fail "$D" "slurmd failed to start"; return 1; }

    # ---- wait for the node to be idle ----
    # "idle" alone is not enough: slurmctld may show a state recovered from
    # DIR/state, so also require that this run's slurmd has registered
    # (SlurmdStartTime not older than this start).
    local ok='' sdt sde t0s=${t0%.*}
    # sinfo/scontrol block ~9 s retrying when slurmctld is not listening yet,
    # hence a wall-clock deadline and a per-call timeout.
    local deadline=$((SECONDS + timeout))
    st=
    while [ "$SECONDS" -lt "$deadline" ]; do
        st=$(SLURM_CONF=$conf timeout 3 sinfo -h -n "$host" -o '%T' 2>/dev/null | head -n1)
        # idle; mixed/allocated only if jobs were recovered from DIR/state
        if [ "$st" = idle ] || [ "$st" = mixed ] || [ "$st" = allocated ]; then
            sdt=$(SLURM_CONF=$conf timeout 3 scontrol -o show node "$host" 2>/dev/null |
                  sed -n 's/.*SlurmdStartTime=\([^ ]*\).*/\1/p')
            sde=$(date -d "$sdt" +%s 2>/dev/null) || sde=0
            [ "$sde" -ge "$t0s" ] && { ok=1; break; }
        fi
        sleep 0.25
    done
    if [ -z "$ok" ]; then
        _sl_fail "$D" "node $host not idle after ${timeout}s (sinfo state: '${st:-no answer}')" \
            "$(SLURM_CONF=$conf timeout 5 sinfo -R 2>&1)"
        return 1
    fi
    _sl_log "cluster up in $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.2f", b-a}') s: node $host $st, ports $cport/$dport"
    _sl_log "use:  export SLURM_CONF=$conf    (or: . $D/env.sh)"
    return 0
}

# wait (bounded) for pid to exit, SIGKILL as a last resort
_sl_kill_wait() {
    local name=$1 pid=$2 i
    kill -TERM "$pid" 2>/dev/null || return 0
    for i in $(seq 1 60); do            # up to 15 s
        kill -0 "$pid" 2>/dev/null || return 0
        sleep 0.25
    done
    _sl_log "$name (pid $pid) ignored SIGTERM for 15 s; sending SIGKILL"
    kill -KILL "$pid" 2>/dev/null
    for i in $(seq 1 20); do
        kill -0 "$pid" 2>/dev/null || return 0
        sleep 0.25
    done
    _sl_die "$name (pid $pid) still alive"
}

# pids (other than this shell) with an open fd under DIR; optional comm filter
_sl_holders() {
    local D=$1 want=${2:-} p pid f
    for p in /proc/[0-9]*; do
        pid=${p#/proc/}
        [ "$pid" = "$$" ] && continue
        [ -n "$want" ] && [ "$(cat "$p/comm" 2>/dev/null)" != "$want" ] && continue
        for f in "$p"/fd/*; do
            case $(readlink "$f" 2>/dev/null) in
                "$D"/*) echo "$pid"; break ;;
            esac
        done
    done
}

# all descendants of the given pids
_sl_descendants() {
    local table frontier="$*" next out='' p
    table=$(ps -eo pid=,ppid=)
    while [ -n "$frontier" ]; do
        next=
        for p in $frontier; do
            next="$next $(printf '%s\n' "$table" | awk -v pp="$p" '$2 == pp {print $1}')"
        done
        # shellcheck disable=SC2086,SC2116  # intentional: squeeze whitespace
        next=$(echo $next)
        out="$out $next"
        frontier=$next
    done
    echo "${out# }"
}

slurm_local_stop() {
    if [ -z "${1:-}" ] || [ ! -d "$1" ]; then
        _sl_die "stop: no such directory '${1:-}'"; return 1
    fi
    local D rc=0 name pid i
    D=$(cd -- "$1" && pwd -P)
    local conf=$D/slurm.conf

    # cancel remaining jobs first, so no slurmstepd/job processes outlive slurmd
    if _sl_alive_pid "$D/run/slurmctld.pid" slurmctld >/dev/null && [ -e "$conf" ]; then
        if [ -n "$(SLURM_CONF=$conf timeout 5 squeue -h -o %A 2>/dev/null)" ]; then
            SLURM_CONF=$conf timeout 5 scancel --quiet --user="$(id -un)" 2>/dev/null
            for i in $(seq 1 60); do
                [ -z "$(SLURM_CONF=$conf timeout 5 squeue -h -o %A 2>/dev/null)" ] && break
                sleep 0.25
            done
        fi
    fi

    # slurmd and slurmctld in parallel (each takes 1-2 s), munged last
    local bg=
    for name in slurmd slurmctld; do
        if pid=$(_sl_alive_pid "$D/run/$name.pid" "$name"); then
            _sl_kill_wait "$name" "$pid" & bg="$bg $!"
        fi
    done
    for pid in $bg; do wait "$pid" || rc=1; done
    if pid=$(_sl_alive_pid "$D/run/munged.pid" munged); then
        _sl_kill_wait munged "$pid" || rc=1
    fi
    rm -f "$D/run/slurmd.pid" "$D/run/slurmctld.pid" "$D/run/munged.pid"
    rm -f "$D/munge.sock" "$D/munge.sock.lock"

    # Jobs that could not be cancelled (e.g. slurmctld already dead) leave an
    # orphaned slurmstepd (it holds DIR/log/slurmd.log open) plus the job's
    # processes: kill those stepds and all their descendants.
    local stepds victims
    stepds=$(_sl_holders "$D" slurmstepd | tr "\n" " ")
    if [ -n "$stepds" ]; then
        # shellcheck disable=SC2086  # pid lists are meant to be split
        victims="$stepds $(_sl_descendants $stepds)"
        _sl_log "killing orphaned slurmstepd/job processes: $victims"
        # shellcheck disable=SC2086
        kill -KILL $victims 2>/dev/null
        for i in $(seq 1 20); do
            local alive=
            for pid in $victims; do kill -0 "$pid" 2>/dev/null && alive=1; done
            [ -z "$alive" ] && break
            sleep 0.25
        done
    fi

    # report anything else still holding files open under DIR
    local left=
    for pid in $(_sl_holders "$D"); do
        left="$left $pid($(cat "/proc/$pid/comm" 2>/dev/null))"
    done
    if [ -n "$left" ]; then
        _sl_log "WARNING: processes still holding files in $D:$left"
        rc=1
    fi
    [ "$rc" = 0 ] && _sl_log "stopped ($D)"
    return $rc
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
    case "${1:-}" in
        start) slurm_local_start "${2:-}" ;;
        stop)  slurm_local_stop  "${2:-}" ;;
        *) echo "usage: $0 start|stop DIR" >&2; exit 2 ;;
    esac
fi
