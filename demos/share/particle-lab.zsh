#compdef particle-lab
# zsh completion for particle-lab: subcommands, then the chosen subcommand's
# options as its --help lists them, files elsewhere.
if (( CURRENT == 2 )); then
  compadd -- ${(f)"$($words[1] --help 2>/dev/null | sed -n 's/^  \([a-z][a-z-]*\)  .*/\1/p')"} --help --version
elif [[ $PREFIX == -* ]]; then
  compadd -- ${(f)"$($words[1] $words[2] --help 2>/dev/null | grep -o -- '--[a-z][a-z-]*' | sort -u)"}
else
  _files
fi
