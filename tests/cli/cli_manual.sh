#!/usr/bin/env bash
# The manual page and the bash completion say what --help says: every flag
# `pelt render --help` lists is in pelt(1)'s RENDER, BENCH AND COMPARE FLAGS, and no
# other; the same for view (render's flags and its own) and atlas; every command; the completion offers the same
# flags, the commands and the scene keys. pelt.1 in the build tree is what
# this pelt prints. Skips (77) without man (Debian package man-db).
#   cli_manual.sh PELT BUILD_DIR
set -u
pelt=$1 build=$2
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
words() { tr ' ' '\n' | grep -v '^$' | sort -u | tr '\n' ' '; }
# Flags in the left column of a --help listing ("  -o, --output FILE  help").
help_flags() {
  "$pelt" "$@" --help | sed -n 's/^  \(-[^ ].*\)$/\1/p' | sed 's/   *.*//' |
    grep -oE '(^|[ ,])--?[a-zA-Z][a-zA-Z0-9-]*' | tr -d ' ,' | words
}

man1="$build/pelt.1"
"$pelt" manpage | cmp -s - "$man1"; check built_page_is_current $? "$man1 differs from 'pelt manpage'"
if ! command -v man >/dev/null; then
  echo "SKIP: man is not installed (Debian package man-db; scripts/setup.sh --tests installs it)"
  [ $fails -eq 0 ] || exit 1
  exit 77
fi
page=$(LC_ALL=C MANWIDTH=100 MANPAGER=cat man "$man1" 2>&1 | col -b); rc=$?
[ $rc -eq 0 ] && grep -q "^NAME" <<<"$page"; check man_shows_the_page $? "exit $rc: $(head -5 <<<"$page")"
# Flag tags of one section: the lines indented by 7 that start with '-'.
section_flags() {
  awk -v s="$1" '/^[A-Z]/ { on = ($0 == s) } on' <<<"$page" | grep -E '^ {7}-' |
    grep -oE '(^|[ ,])--?[a-zA-Z][a-zA-Z0-9-]*' | tr -d ' ,' | words
}

want=$(help_flags render); got=$(section_flags "RENDER, BENCH AND COMPARE FLAGS")
[ -n "$want" ] && [ "$want" = "$got" ]
check man_has_every_render_flag $? "render --help: $want
man: $got"
[ "$(help_flags bench)" = "$want" ]; check bench_takes_the_same_flags $? "$(help_flags bench)"
want=$(help_flags view); got=$(section_flags "VIEW FLAGS")
[ -n "$want" ] && [ "$want" = "$got" ]; check man_has_every_view_flag $? "view --help: $want
man: $got"
extra=$(comm -13 <(help_flags render | tr ' ' '\n' | sort) <(help_flags view | tr ' ' '\n' | sort) | tr '\n' ' ')
[ "$extra" = "--no-hud --screenshot-at --script " ]; check view_takes_render_flags_and_its_own $? "view's own: $extra"
want=$(help_flags atlas); got=$(section_flags "ATLAS FLAGS")
[ -n "$want" ] && [ "$want" = "$got" ]; check man_has_every_atlas_flag $? "atlas --help: $want
man: $got"
commands=$("$pelt" --help | sed -n '/^commands:/,/^$/s/^  \([a-z]*\) .*/\1/p' | words)
got=$(awk '/^[A-Z]/ { on = ($0 == "COMMANDS") } on' <<<"$page" | sed -n 's/^       \([a-z]*\).*/\1/p' | words)
[ -n "$commands" ] && [ "$commands" = "$got" ]; check man_has_every_command $? "help: $commands; man: $got"

# Completion: complete words as bash would for pelt ARGS... (last one the
# word being completed) and print them sorted.
comp=$("$pelt" completion bash); check completion_prints $? ""
bash -n <<<"$comp"; check completion_is_bash $? "syntax error"
complete_words() {
  bash -c 'source /dev/stdin; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _pelt
           printf "%s\n" "${COMPREPLY[@]}"' pelt "$@" <<<"$comp" | words
}
[ "$(complete_words pelt '')" = "$(echo "$commands --help --version" | words)" ]
check completion_commands $? "$(complete_words pelt '')"
want="$(help_flags render)"
[ "$(complete_words pelt render -)" = "$want" ]; check completion_render_flags $? "$(complete_words pelt render -)"
[ "$(complete_words pelt view -)" = "$(help_flags view)" ]; check completion_view_flags $? "$(complete_words pelt view -)"
[ "$(complete_words pelt atlas -)" = "$(help_flags atlas)" ]; check completion_atlas_flags $? "$(complete_words pelt atlas -)"
# Scene keys for --set: the ones the scene parser takes (each must be
# accepted as a key: a wrong value names the key, an unknown key says so).
keys=$(complete_words pelt render --set '')
n=$(wc -w <<<"$keys")
[ "$n" -ge 50 ] && grep -q "fur.layers=" <<<"$keys" && grep -q "wetness.rain.rate=" <<<"$keys"
check completion_scene_keys $? "$n keys: $keys"
bad=""
for k in $keys; do
  err=$("$pelt" render --size 8x8 --set "${k}@" -o /dev/null 2>&1)
  grep -q "unknown key" <<<"$err" && bad="$bad $k"
done
[ -z "$bad" ]; check completion_keys_are_scene_keys $? "unknown to pelt:$bad"
[ "$(complete_words pelt render --preset w)" = "wavy " ]; check completion_preset_values $? "$(complete_words pelt render --preset w)"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
