#!/usr/bin/env bash
# Wrapper for bench/run_bench.py with Debian's python3 (all arguments pass through).
#   bash bench/run_bench.sh --quick --out /tmp/bench
exec /usr/bin/python3 "$(cd "$(dirname "$0")" && pwd)/run_bench.py" "$@"
