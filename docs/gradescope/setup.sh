#!/usr/bin/env bash
# Gradescope runs this once, when it builds the autograder image (Ubuntu, as root).
# The autograder zip holds setup.sh, run_autograder and exams/ (a `robosolve variants
# --roster` folder: variants.csv, roster.csv, one <name>-<variant>/problem.yaml each).
set -euo pipefail
apt-get update -y
apt-get install -y python3 python3-pip
pip3 install --no-cache-dir "${ROBOSOLVE_SPEC:-robosolve}"
