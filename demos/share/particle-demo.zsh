#compdef particle-demo
# zsh completion for particle-demo: its options as --help lists them, files elsewhere.
if [[ $PREFIX == -* ]]; then
  compadd -- ${(f)"$($words[1] --help 2>/dev/null | grep -o -- '--[a-z][a-z-]*' | sort -u)"}
else
  _files
fi
