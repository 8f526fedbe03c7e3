# Helpers for the measurement scripts (sourced: . "$TRADEOFF_DIR/lib.sh").
# The environment is the one tools/run-tradeoff.sh sets.

tr_die() { echo "$0: $*" >&2; exit 1; }

# tr_need FILE...: each must be an executable (a program of the build)
tr_need() {
    for f in "$@"; do
        [ -x "$f" ] || tr_die "$f: not built (make tradeoff builds it)"
    done
}

# tr_plot NAME TITLE CSV_FILES GNUPLOT_COMMANDS
# Writes $OUT/NAME.gp (the style, the output NAME.png, the commands; data
# files are named relative to $OUT) and, when GNUPLOT is set, runs it in $OUT.
# Prints the section's Markdown for the plot: the image, or without gnuplot
# the data files and the command that draws it.
tr_plot() {
    name=$1; title=$2; csvs=$3; cmds=$4
    {
        echo "# $title (tools/run-tradeoff.sh; data: $csvs)"
        echo "load '$TRADEOFF_DIR/style.gp'"
        echo "set output '$name.png'"
        printf '%s\n' "$cmds"
    } >"$OUT/$name.gp"
    if [ -n "$GNUPLOT" ]; then
        if (cd "$OUT" && "$GNUPLOT" "$name.gp" 2>"$name.gp.log"); then
            echo "![$title]($name.png)"
            return 0
        fi
        echo "gnuplot failed on $OUT/$name.gp:" >&2
        cat "$OUT/$name.gp.log" >&2
        echo "(gnuplot failed on \`$name.gp\`: the data is in $csvs)"
        return 1
    fi
    echo "*$title*: data in $csvs; without gnuplot in this run, plot it with"
    echo "\`cd $OUT && gnuplot $name.gp\`."
}

# tr_csv_value FILE COLUMN_NAME ROW_KEY_COLUMN ROW_KEY: one value of a CSV
# with a header line (plain fields, no quoted commas)
tr_csv_value() {
    awk -F, -v col="$2" -v kc="$3" -v key="$4" '
        NR == 1 { for (i = 1; i <= NF; ++i) { if ($i == col) c = i; if ($i == kc) k = i } next }
        c && k && $k == key { print $c; exit }' "$1"
}
