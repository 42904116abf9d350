# Helpers of the efficiency scripts (sourced; the caller sets $dir, a
# scratch directory).
cpu() { # prints the CPU seconds (user + sys) of the command
  /usr/bin/time -f "%U %S" -o "$dir/time" "$@" >/dev/null 2>&1
  awk '{print $1 + $2}' "$dir/time"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
