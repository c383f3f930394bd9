#!/bin/sh
# Doxygen input filter for the Markdown pages of doc/ (FILTER_PATTERNS in doc/Doxyfile).
# The pages are written for GitHub's renderer; Doxygen reads them with three changes, which
# leave the files themselves alone:
# - in table rows, `#word` (e.g. compare's "#v: 1907 #f: 3671") is text, not a link request;
# - links to a heading (`[text](#heading)`, `[text](page.md#heading)`) lose the heading part,
#   since Doxygen 1.9 makes no anchors from Markdown headings: they point at the page;
# - links out of doc/ (`../README.md`) become plain text: the README is not in the reference;
# - links to the concepts (`[text](Concepts/NAME.dox)`, `[text](Concepts)`), files that GitHub
#   shows as they are, become references to the concept's page (class NAME) and to the group of
#   the concepts;
# - the title of page `doc/NAME.md` gets the label NAME, so the page is `NAME.html` (not a
#   name made of the absolute path of the file); index.md is the main page already.
# Doxygen calls it as `doc/doxygen_md_filter.sh FILE` and reads its stdout.
name=$(basename "$1" .md)
label=""
[ "$name" = index ] || label=" {#$name}"
exec sed \
  -e "0,/^# / s/^\(# .*\)\$/\1$label/" \
  -e '/^|/ s/\([ |(]\)#\([A-Za-z]\)/\1\\#\2/g' \
  -e 's/\[\([^]]*\)\](Concepts\/\([A-Za-z_]*\)\.dox)/\\ref \2 "\1"/g' \
  -e 's/\[\([^]]*\)\](Concepts)/\\ref PkgICMConcepts "\1"/g' \
  -e 's/\[\([^]]*\)\](#[^)]*)/\1/g' \
  -e 's/\[\([^]]*\)\](\.\.\/[^)]*)/\1/g' \
  -e 's/\(\]([^)#]*\.md\)#[^)]*)/\1)/g' \
  "$1"
