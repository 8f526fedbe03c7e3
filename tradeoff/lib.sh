# Helpers for the measurement scripts (sourced: . "$TRADEOFF_DIR/lib.sh").
# The environment is the one tools/run-tradeoff.sh sets.

tr_die() { echo "$0: $*" >&2; exit 1; }

# tr_need FILE...: each must be an executable (a program of the build)
tr_need() {
    for f in "$@"; do
        [ -x "$f" ] || tr_die "$f: not built (make tradeoff builds it)"
    done
}

# tr_plot NAME TITLE CSV_FILES GNUPLOT_COMMANDS [TERMINAL_OPTIONS]
# Writes $OUT/NAME.gp (the style, the output NAME.png, the commands; data
# files are named relative to $OUT) and, when GNUPLOT is set, runs it in $OUT.
# TERMINAL_OPTIONS (e.g. "size 1100,560 enhanced font 'DejaVu Sans,9'")
# replace the style's pngcairo options, for a plot of several panels.
# Prints the section's Markdown for the plot: the image, or without gnuplot
# the data files and the command that draws it. Status 1 when gnuplot failed.
tr_plot() {
    _tp_name=$1; _tp_title=$2; _tp_csvs=$3; _tp_cmds=$4; _tp_term=${5:-}
    {
        echo "# $_tp_title (tools/run-tradeoff.sh; data: $_tp_csvs)"
        echo "load '$TRADEOFF_DIR/style.gp'"
        [ -n "$_tp_term" ] && echo "set terminal pngcairo $_tp_term"
        echo "set output '$_tp_name.png'"
        printf '%s\n' "$_tp_cmds"
    } >"$OUT/$_tp_name.gp"
    if [ -n "$GNUPLOT" ]; then
        if (cd "$OUT" && "$GNUPLOT" "$_tp_name.gp" 2>"$_tp_name.gp.log"); then
            rm -f "$OUT/$_tp_name.gp.log"
            echo "![$_tp_title]($_tp_name.png)"
            return 0
        fi
        echo "gnuplot failed on $OUT/$_tp_name.gp:" >&2
        cat "$OUT/$_tp_name.gp.log" >&2
        echo "(gnuplot failed on \`$_tp_name.gp\`: the data is in $_tp_csvs)"
        return 1
    fi
    echo "*$_tp_title*: data in $_tp_csvs; without gnuplot in this run, plot it with"
    echo "\`cd $OUT && gnuplot $_tp_name.gp\`."
}

# tr_g3 VALUE: a number to three significant digits for the report's prose
# (anything else as it is)
tr_g3() {
    awk -v x="$1" 'BEGIN { if (x ~ /^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$/) printf "%.3g\n", x; else print x }'
}

# tr_csv_value FILE COLUMN_NAME ROW_KEY_COLUMN ROW_KEY: one value of a CSV
# with a header line (plain fields, no quoted commas)
tr_csv_value() {
    awk -F, -v col="$2" -v kc="$3" -v key="$4" '
        NR == 1 { for (i = 1; i <= NF; ++i) { if ($i == col) c = i; if ($i == kc) k = i } next }
        c && k && $k == key { print $c; exit }' "$1"
}
