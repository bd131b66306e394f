#!/usr/bin/env bash
# --turntable end to end, on the built-in default scene at 64x36: N files named from --output's
# stem with the frame number; neighbouring frames differ; frame 0 is the plain still; a frame
# depends only on its angle (frame 2 of 4 equals frame 1 of 2, both half a turn), which with
# test_turntable's camera(N) = camera(0) makes the loop seamless; progress on stderr; video
# output through ffmpeg (a stand-in that records its arguments, and the real one when installed)
# and a clear error when ffmpeg is missing; bad values refused.
#   usage: cli_turntable.sh SHADELAB SL-IMGDIFF OUTDIR
set -u
exe=$1 imgdiff=$2 out=$3
mkdir -p "$out"
. "$(dirname "$0")/cli_check.sh"
# tone mapping's dither is noise that changes with the frame index (within one 8-bit code
# value): off here, so that equal cameras give equal images
size="64x36 --set tonemap.dither=false"
msg=$("$exe" --headless --size $size --turntable 4 --output "$out/tt.png" 2>&1)
check test $? -eq 0
for k in 000 001 002 003; do check test -s "$out/tt-$k.png"; done
check test ! -e "$out/tt-004.png"
check test ! -e "$out/tt.png"
check grep -qF "turntable: frame 4 of 4" <<<"$msg"
check grep -qF "wrote 4 frames $out/tt-000.png ... $out/tt-003.png" <<<"$msg"
# the camera moves: every frame differs from the one before, and the last from the first
for pair in "000 001" "001 002" "002 003" "003 000"; do
    set -- $pair
    check "$imgdiff" "$out/tt-$1.png" "$out/tt-$2.png" --differ 0.005
done
# frame 0 is the start camera's still (1/255: one 8-bit code value)
check "$exe" --headless -q --size $size --output "$out/still.png"
check "$imgdiff" "$out/tt-000.png" "$out/still.png" --same 0.0040
# a frame is a still of its angle, whatever came before it
check "$exe" --headless -q --size $size --turntable 2 --output "$out/half.png"
check "$imgdiff" "$out/tt-002.png" "$out/half-001.png" --same 0.0040
check "$imgdiff" "$out/half-000.png" "$out/still.png" --same 0.0040
# the default output name: out-000.png ...; -q keeps stderr quiet
( cd "$out" && "$exe" --headless -q --size 16x9 --scene "$(dirname "$0")/../scenes/basic.json" --turntable 3 ) > "$out/q.log" 2>&1
check test $? -eq 0
check test -s "$out/out-002.png"
check test ! -s "$out/q.log"

# video: ffmpeg missing → a clear error before anything renders
mkdir -p "$out/nobin"
msg=$(PATH="$out/nobin" "$exe" --headless --size 16x16 --turntable 2 --output "$out/v.mp4" 2>&1)
rc=$?
check test $rc -ne 0
check grep -qF "needs ffmpeg, which is not installed" <<<"$msg"
check test ! -e "$out/v.mp4"
# a stand-in ffmpeg: records its arguments and the frames it was given, writes the output
mkdir -p "$out/fakebin"
cat > "$out/fakebin/ffmpeg" <<'SH'
#!/bin/sh
echo "$@" > "$FAKE_LOG"
prev=
for a in "$@"; do
  if [ "$prev" = "-i" ]; then ls "$(dirname "$a")" > "$FAKE_LOG.frames"; fi
  prev=$a; last=$a
done
echo video > "$last"
SH
chmod +x "$out/fakebin/ffmpeg"
FAKE_LOG="$out/fake.log" PATH="$out/fakebin:$PATH" "$exe" --headless -q --size 16x16 --scene "$(dirname "$0")/../scenes/basic.json" \
    --turntable 3 --output "$out/v.mp4"
check test $? -eq 0
check test -s "$out/v.mp4"
check grep -q -- "-framerate 30 -i .*/frame-%03d.png .* -pix_fmt yuv420p $out/v.mp4" "$out/fake.log"
check test "$(cat "$out/fake.log.frames" 2>/dev/null | tr '\n' ' ')" = "frame-000.png frame-001.png frame-002.png "
tmpdir=$(sed -n 's/.* -i \(.*\)\/frame-%03d.png.*/\1/p' "$out/fake.log")
check test -n "$tmpdir"
check test ! -e "$tmpdir"       # the frames are removed after encoding
# the real ffmpeg when installed (optional dependency)
if command -v ffmpeg >/dev/null; then
    check "$exe" --headless -q --size 33x17 --scene "$(dirname "$0")/../scenes/basic.json" --turntable 4 --output "$out/real.mp4"
    check test -s "$out/real.mp4"
else
    echo "note: ffmpeg not installed; the real encoder was not run (the stand-in was)"
fi

expect_error "--turntable 0: expected a whole number" --turntable 0
expect_error "--turntable x: expected a whole number" --turntable x
expect_error "--turntable renders its own frames" --turntable 2 --frames 3
expect_error "a video is written by --turntable N" --output "$out/x.mp4"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
