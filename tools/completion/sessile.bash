# bash completion for sessile (docs/install.md).
# Every list comes from the sessile being completed, so nothing here goes
# stale: commands and generators from `sessile --help`, subcommands from the
# usage lines of `sessile CMD --help` ("sessile bench la|grow|..."), options
# from the help of the command typed, parameter names after --set from
# `sessile CMD --print-config` (the generators' parameter tables).  None of
# these needs a Vulkan device; each answers in milliseconds.

# The options, of every command, whose next word is a value and not a
# command word.
_sessile_takes_value() {
  case $1 in
    --device|--precision|--set|--config|--out|-o|--resume|--seed|--iterations|--every|--preset|\
    --grammar|--define|--max-memory|--slices|--t-end|--frames|--max-cells|--max-steps|--size|\
    --view|--turntable|--samples|--background|--color-by|--colormap|--units|--channel|--outline|\
    --range|--sheet|--caption|--repeat|--mg|--obj-axes|--progress|-j|--jobs) return 0 ;;
  esac
  return 1
}

_sessile() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}
  local bin=${COMP_WORDS[0]} i w
  local -a cmd=()
  # The command words (sessile [global options] WORD [WORD [MODEL]]): they
  # end at the first option after the command.
  for ((i = 1; i < COMP_CWORD; i++)); do
    w=${COMP_WORDS[i]}
    if [[ $w == -* ]]; then
      ((${#cmd[@]})) && [[ $w != --device && $w != --precision && $w != --validation ]] && break
      _sessile_takes_value "$w" && ((i++))
    elif _sessile_takes_value "${COMP_WORDS[i-1]}"; then
      continue
    else
      cmd+=("$w")
    fi
  done

  case $prev in
    --set)
      local names
      names=$("$bin" "${cmd[@]}" --print-config 2>/dev/null | awk 'NR > 1 { print $1 "=" }' | sort -u)
      compopt -o nospace 2>/dev/null
      COMPREPLY=($(compgen -W "$names" -- "$cur"))
      return ;;
    --config|--outline|-o|--out|--grammar)
      COMPREPLY=($(compgen -f -- "$cur"))
      return ;;
    --resume)
      COMPREPLY=($(compgen -d -- "$cur"))
      return ;;
    --precision)
      COMPREPLY=($(compgen -W "32 64" -- "$cur"))
      return ;;
    --obj-axes)
      COMPREPLY=($(compgen -W "zup-cm yup-m" -- "$cur"))
      return ;;
    --progress)
      COMPREPLY=($(compgen -W "auto tty lines json none" -- "$cur"))
      return ;;
  esac
  _sessile_takes_value "$prev" && return

  if [[ $cur == -* ]]; then
    local opts
    opts=$({ "$bin" --help; ((${#cmd[@]})) && "$bin" "${cmd[@]}" --help; } 2>/dev/null |
           grep -oE -- '(^|[][ ,|])--?[a-z][a-z0-9-]*' | sed 's/^[][ ,|]*//' | sort -u)
    opts+=" --help --version"
    COMPREPLY=($(compgen -W "$opts" -- "$cur"))
  elif ((${#cmd[@]} == 0)); then
    # the first word of every line under "commands:" and "generators ...:"
    local names
    names=$("$bin" --help 2>/dev/null |
            awk '/^[a-z].*:$/ { on = ($1 == "commands:" || $1 == "generators") ; next }
                 /^$/ { on = 0 } on && /^  [a-z]/ { print $1 }' | sort -u)
    COMPREPLY=($(compgen -W "$names" -- "$cur"))
  elif ((${#cmd[@]} == 1)); then
    local subs
    subs=$("$bin" "${cmd[0]}" --help 2>/dev/null |
           grep -oE "sessile ${cmd[0]} [a-z][a-z|]*" | awk '{ print $3 }' | tr '|' '\n' | sort -u)
    if [[ -n $subs ]]; then
      COMPREPLY=($(compgen -W "$subs" -- "$cur"))
    else
      COMPREPLY=($(compgen -f -- "$cur"))
    fi
  else
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}
complete -o filenames -o bashdefault -F _sessile sessile
