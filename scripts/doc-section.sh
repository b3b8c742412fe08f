# Sourced by the scripts that keep a generated table in a document between the markers
# <!-- NAME:begin --> and <!-- NAME:end -->: one reader and one writer of such a section.

# Prints the lines between NAME's markers in DOC.
doc_section_print() {  # NAME DOC
  awk -v name="$1" '$0 == "<!-- " name ":end -->" { inside = 0 } inside { print } $0 == "<!-- " name ":begin -->" { inside = 1 }' "$2"
}

# Replaces the lines between NAME's markers in DOC with the file TABLE, atomically.
doc_section_replace() {  # NAME TABLE DOC
  awk -v name="$1" -v table="$2" '
    $0 == "<!-- " name ":begin -->" { print; while ((getline line < table) > 0) print line; skipping = 1; next }
    $0 == "<!-- " name ":end -->" { skipping = 0 }
    !skipping { print }
  ' "$3" >"$3.tmp" && mv "$3.tmp" "$3"
}
