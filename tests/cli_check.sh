# Sourced by the command-line test scripts (cli_scenes.sh, cli_turntable.sh): counters and the two
# checks they share. Needs $exe (the shadelab executable); expect_error runs it headless at 16x16
# with the arguments in the array expect_error_args (empty by default) before its own.
fail=0 pass=0
expect_error_args=()
check() { if "$@"; then pass=$((pass+1)); else echo "FAILED: $*"; fail=$((fail+1)); fi; }
expect_error() { # expect_error FRAGMENT ARGS...: exits non-zero and says FRAGMENT
    local frag=$1; shift
    local msg
    msg=$("$exe" --headless --size 16x16 "${expect_error_args[@]}" "$@" 2>&1)
    local rc=$?
    if [ $rc -ne 0 ] && grep -qF -- "$frag" <<<"$msg"; then pass=$((pass+1)); else
        echo "FAILED: '$*' gave rc=$rc: $msg (expected '$frag')"; fail=$((fail+1)); fi
}
