#!/usr/bin/env bash
# Validates every program variant, exactly as the renderer composes it, with glslangValidator (GLSL ES 1.00 because
# each source starts with "#version 100"). Usage: check_shaders_glslang.sh <obscura-shaders binary>
#
# glslang-gles2-limits.conf is glslangValidator's default resource file (glslangValidator -c) with two changes:
# - the limitations of GLSL ES 1.00 Appendix A switched on (glslang waives them by default): for loops whose index
#   is initialised, compared and stepped only as "i++, i--, i += c, i -= c" with constants (so "++i" is refused),
#   no while / do-while, and no dynamic indexing beyond what Appendix A requires of every implementation;
# - OpenGL ES 2.0's minimum texture units, vertex attributes and draw buffers (ES 2.0 spec, table 6.20), so a
#   shader that only runs where a driver offers more is caught.
#
# glslang does not know GL_EXT_draw_buffers. A variant that requires it (only built where the context offers it) is
# checked without its #extension line under the extension's own guarantee: MAX_DRAW_BUFFERS_EXT is at least 4
# (EXT_draw_buffers, WEBGL_draw_buffers), which gives gl_FragData[] that many elements.
set -euo pipefail
shopt -s nullglob
limits="$(dirname "$0")/glslang-gles2-limits.conf"
dump=$(mktemp -d)
trap 'rm -rf "$dump"' EXIT
"$1" --dump "$dump"
sed 's/^MaxDrawBuffers 1$/MaxDrawBuffers 4/' "$limits" > "$dump/draw-buffers-limits.conf"
grep -q '^MaxDrawBuffers 4$' "$dump/draw-buffers-limits.conf"
# One glslangValidator run per limits file (it compiles each file named as a unit of its own and names the file in
# its messages): a process per stage took most of a minute for the 900 stages.
plain=()
drawBuffers=()
declare -A needsDrawBuffers=()
while IFS= read -r file; do needsDrawBuffers["$file"]=1; done < <(grep -l '^#extension GL_EXT_draw_buffers' "$dump"/*)
for file in "$dump"/*.vert "$dump"/*.frag; do
  if [ -n "${needsDrawBuffers[$file]:-}" ]; then
    # Keep the line count, so glslang's line numbers still match the dumped file.
    sed -i 's/^#extension GL_EXT_draw_buffers.*$/\/\/ (#extension GL_EXT_draw_buffers: checked with MaxDrawBuffers 4)/' "$file"
    drawBuffers+=("$file")
  else
    plain+=("$file")
  fi
done
validate() {
  local limitsFile="$1"
  shift
  [ "$#" -gt 0 ] || return 0
  if ! out=$(glslangValidator "$limitsFile" "$@" 2>&1); then
    echo "glslangValidator rejected stages (each message follows the file it is about):"
    echo "$out" | grep -B1 -A3 'ERROR' || echo "$out"
    exit 1
  fi
}
validate "$limits" "${plain[@]}"
validate "$dump/draw-buffers-limits.conf" "${drawBuffers[@]}"
count=$((${#plain[@]} + ${#drawBuffers[@]}))
echo "glslangValidator accepted $count shader stages as GLSL ES 1.00 under Appendix A and GLES 2 minimum limits" \
     "(${#drawBuffers[@]} with MaxDrawBuffers 4)"
[ "$count" -ge 40 ]
