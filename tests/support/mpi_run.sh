# Sourced by the MPI test scripts, after they set exe (emergent), mpirun and dir (a scratch
# folder): run NP ARGS... runs `emergent run ARGS...` on NP ranks; when it exits non-zero, it
# prints the command and the run's last lines and exits 1.
run() {
    local np=$1; shift
    if ! "$mpirun" -q --allow-run-as-root --oversubscribe -np "$np" "$exe" run "$@" >"$dir/last.log" 2>&1; then
        echo "FAIL: emergent run $* on $np rank(s) exited non-zero:"; tail -5 "$dir/last.log"; exit 1
    fi
}
