#!/usr/bin/env bash
# Re-makes the committed teleoperation recordings in test/data/teleop/ (README.md there) through
# vb_view's real teleoperation path, driven by scripts/teleop_scripted_drive.py: drive_001 holds
# W (and a little A, then D) until the goal is reached (success), drive_002 holds W for 0.6 s, brakes
# and is stopped by its operator after 2 s (not a success). Needed when the physics changes:
# the recordings replay bit for bit only on a build with the physics that recorded them
# (vb_collect teleop checks it, VbCollectTest.TeleopRecordingsBecomeDemonstrations fails).
# Usage: scripts/make_teleop_recording.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=test/data/teleop
rm -rf "$out/drive_001" "$out/drive_002"
python3 scripts/teleop_scripted_drive.py --vb-view "$build/tools/vb_view" \
    --task "$out/teleop_demo.yaml" --vehicle hmmwv --pair 0 --seed 0 --operator scripted \
    --out "$out" "W@0-10,A@0.8-1.1,D@1.4-1.7" "W@0-0.6,S@0.6-2,stop@2"
ls -l "$out"/drive_00*/
