#!/usr/bin/env bash
# What a user reads cites only what the repository ships (issue 35, item 7): no text, --help page or
# message names SPEC.md or the thesis's equation numbers bare ("eq. 2.48"), and every equation
# reference "eq. Pn" names an equation that docs/physics.md numbers.
# Usage: user_docs.sh SOURCE_DIR BUILD_DIR
set -u
src=$1
build=$2
fail=0
bad() { echo "FAIL $*"; fail=1; }
ok() { echo "ok   $*"; }

cd "$src" || exit 1
docs=(README.md docs/*.md workflows/*/README.md workflows/*/*.toml workflows/*/*.mk scripts/*.py scripts/*.sh)

# 1. No text cites SPEC.md (which users do not have), nor a thesis equation number as if it were ours.
#    (The thesis is credited as "[thesis 2.48]" or "thesis §4.5" in prose.)
hits=$(grep -nE 'SPEC(\.md| ?§|'"'"'s)|\beq\. ?[0-9]+\.[0-9]+' "${docs[@]}")
if [ -n "$hits" ]; then bad "docs cite SPEC or bare thesis equations:"; echo "$hits"; else ok "docs cite no SPEC and no bare thesis equation (${#docs[@]} files)"; fi

# 2. The same for what the tools print: --help pages, and every string compiled into the tools and
#    the libraries (error and warning messages, the units the scene parser quotes).
tools=(gen-primary copy-settle compact run-stage post-macro)
for t in "${tools[@]}"; do
  exe="$build/tools/$t"
  [ -x "$exe" ] || { bad "$exe missing"; continue; }
  h=$("$exe" --help 2>&1 | grep -nE 'SPEC|\beq\. ?[0-9]+\.[0-9]+')
  [ -z "$h" ] && ok "$t --help cites no SPEC" || { bad "$t --help:"; echo "$h"; }
done
bins=("${tools[@]/#/$build/tools/}")
mapfile -t libs < <(find "$build/lib" -maxdepth 1 -name 'libdem*.so*' -type f)
[ ${#libs[@]} -ge 2 ] || bad "libraries not found under $build/lib"
strs=$(strings -n 6 "${bins[@]}" "${libs[@]}" | grep -E 'SPEC( §|\.md|'"'"'s)|\beq\. ?[0-9]+\.[0-9]+' | sort -u)
[ -z "$strs" ] && ok "no message in the tools or libraries cites SPEC or a bare thesis equation" || { bad "messages:"; echo "$strs"; }

# 3. Every "eq. Pn" (and "Pa–Pb") reference exists in docs/physics.md, whose equations are
#    numbered once each, in increasing order (P1, P2, ...; a feature may take a range of its own
#    further up, P60 on, so that work in parallel does not collide).
labels=$(grep -oE '\(P[0-9]+\) *$' docs/physics.md | grep -oE '[0-9]+')
n=$(echo "$labels" | wc -l)
if [ "$labels" = "$(echo "$labels" | sort -nu)" ] && [ "$(echo "$labels" | head -1)" = 1 ]; then
  ok "docs/physics.md numbers $n equations once each, in increasing order from P1"
else
  bad "docs/physics.md labels not once each in increasing order from P1: $(echo $labels)"
fi
refs=$( { cat "${docs[@]}"; strings -n 6 "${bins[@]}" "${libs[@]}"; } | grep -oE 'eq\. P[0-9]+([–-]P[0-9]+)?' | grep -oE '[0-9]+' | sort -un)
[ -n "$refs" ] || bad "no eq. Pn reference found at all"
missing=""
for r in $refs; do echo "$labels" | grep -qx "$r" || missing="$missing P$r"; done
inner=$(grep -oE '\bP[0-9]+\b' docs/physics.md | grep -oE '[0-9]+' | sort -un)
for r in $inner; do echo "$labels" | grep -qx "$r" || missing="$missing P$r(in physics.md)"; done
[ -z "$missing" ] && ok "every eq. Pn cited ($(echo $refs | wc -w) numbers) exists in docs/physics.md" || bad "cited but not in docs/physics.md:$missing"

# 4. A message that cites physics.md really reaches the user: a given time step above the critical one.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/s.toml" <<'EOF'
[simulation]
time_step = 1.0
[[material]]
name = "m"
density = 2500
kn = 1e5
[generation]
box_min = [0.0, 0.0, 0.0]
box_max = [0.02, 0.02, 0.02]
count = 5
radius_min = 0.002
radius_max = 0.002
seed = 1
materials = { m = 1.0 }
EOF
out=$("$build/tools/gen-primary" --scene "$tmp/s.toml" --out "$tmp/o.h5" --quiet 2>&1); rc=$?
if [ $rc -eq 3 ] && echo "$out" | grep -q "exceeds the critical time step .* s of docs/physics.md eq. P5"; then ok "a time step above the critical one cites docs/physics.md eq. P5 (exit 3)"
else bad "time step message (rc $rc): $out"; fi

exit $fail
