# Sourced by the MPI test scripts with their arguments EMERGENT MPIRUN: sets exe, mpirun, here
# (the script's folder) and dir (a scratch folder removed on exit), and defines
# run NP ARGS...: `emergent run ARGS...` on NP ranks; when it exits non-zero, it prints the
# command and the run's last lines and exits 1.
exe=$1
mpirun=$2
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
run() {
    local np=$1; shift
    if ! "$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" run "$@" >"$dir/last.log" 2>&1; then
        echo "FAIL: emergent run $* on $np rank(s) exited non-zero:"; tail -5 "$dir/last.log"; exit 1
    fi
}
