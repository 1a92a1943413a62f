# bash completion for particle-demo: its options as --help lists them, files
# elsewhere.
_particle_demo() {
  local cur prev words cword
  _init_completion || return
  if [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$("${words[0]}" --help 2>/dev/null | grep -o -- '--[a-z][a-z-]*' | sort -u)" -- "$cur"))
  else
    _filedir
  fi
}
complete -F _particle_demo particle-demo
