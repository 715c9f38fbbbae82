# shellcheck shell=bash
# bench/tool_runs.sh: tool runs in the background, JOBS at a time, for the scripts that run yosys and nextpnr
# (bench/rtl_cost.sh, bench/timing.sh). Source it (after setting runs_name, the script's name); then
#   need TOOL PACKAGE  says when TOOL is missing, naming its Debian package, and sets missing=1;
#   launch LOG CMD...  runs CMD in the background with stdout and stderr to LOG, at most $JOBS at a time;
#   finish             waits for every launched command; on a failure shows the end of its log and exits non-zero
#                      (the message starts with $runs_name);
#   work_dir           makes a temporary directory, $tmp, which the script's exit removes after it has killed the
#                      commands still running.
runs_name="${runs_name:-bench}"
pids=()
logs=()
missing=0  # set by need; the sourcing script reads it

need() {
  if ! command -v "$1" >/dev/null 2>&1; then
    echo "$runs_name: $1 not found: install the Debian package $2 (apt-get install $2)" >&2
    # shellcheck disable=SC2034  # the sourcing script reads it
    missing=1
  fi
}

launch() {
  local log="$1"
  shift
  while (($(jobs -pr | wc -l) >= JOBS)); do wait -n || true; done
  "$@" >"$log" 2>&1 &
  pids+=("$!")
  logs+=("$log")
}

finish() {
  local i
  for i in "${!pids[@]}"; do
    if ! wait "${pids[$i]}"; then
      echo "$runs_name: failed, see the end of ${logs[$i]}:" >&2
      tail -n 20 "${logs[$i]}" >&2
      exit 1
    fi
  done
  pids=()
  logs=()
}

stop_runs() {
  local p
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
}

work_dir() {
  tmp="$(mktemp -d)"
  trap 'stop_runs; rm -rf "$tmp"' EXIT
}
