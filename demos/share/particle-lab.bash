# bash completion for particle-lab: subcommands, then the chosen subcommand's
# options as its --help lists them, integrator and scene names after
# --integrator and --scene, files elsewhere.
_particle_lab() {
  local cur prev words cword
  _init_completion || return
  local sub="" w
  for w in "${words[@]:1:cword-1}"; do
    case "$w" in -*) ;; *) sub="$w"; break ;; esac
  done
  if [ -z "$sub" ]; then
    COMPREPLY=($(compgen -W "$("${words[0]}" --help 2>/dev/null | sed -n 's/^  \([a-z][a-z-]*\)  .*/\1/p') --help --version" -- "$cur"))
    return
  fi
  case "$prev" in
    --integrator)
      COMPREPLY=($(compgen -W "$("${words[0]}" list 2>/dev/null | sed -n '/^integrators/,$ s/^  \([a-z0-9][a-z0-9-]*\) .*/\1/p')" -- "$cur"))
      return ;;
    --scene)
      COMPREPLY=($(compgen -W "$("${words[0]}" list 2>/dev/null | sed -n '/^scenes/,/^integrators/ s/^  \([a-z][a-z-]*\)  .*/\1/p')" -- "$cur"))
      return ;;
  esac
  if [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$("${words[0]}" "$sub" --help 2>/dev/null | grep -o -- '--[a-z][a-z-]*' | sort -u)" -- "$cur"))
  else
    _filedir
  fi
}
complete -F _particle_lab particle-lab
