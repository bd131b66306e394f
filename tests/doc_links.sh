#!/usr/bin/env bash
# Every relative link in the project's Markdown files resolves: the file or folder exists and,
# for a link with #anchor, the target file has a heading with that anchor (GitHub's rule: lower
# case, punctuation and symbols other than '-' and '_' dropped, spaces to '-'; other non-ASCII
# letters kept). External links (http:, https:, mailto:) are not checked.
# Usage: tests/doc_links.sh SOURCE_DIR
set -uo pipefail
src=${1:?usage: doc_links.sh SOURCE_DIR}
cd "$src" || exit 1

# The anchors of a Markdown file's headings, one a line (fenced code blocks skipped).
anchors() {
    awk '/^```/ { fence = !fence; next } !fence && /^#+ / { sub(/^#+ +/, ""); print }' "$1" |
        tr 'A-Z' 'a-z' | LC_ALL=C sed -E -e 's/[]!"#$%&'"'"'()*+,./:;<=>?@[\\^`{|}~]//g' \
            -e 's/—|–|·|²|³|×|…|’|‘|“|”|→|←|≤|≥|±|°|≈//g' -e 's/ /-/g'
}

# Markdown files of the project: everything but build trees and nested checkouts.
mapfile -t files < <(find . -name '*.md' -not -path './build*' -not -path '*/build-*' \
    -not -path './.git/*' -not -path './shared/*' | sort)
[ ${#files[@]} -gt 0 ] || { echo "doc_links: no Markdown files under $src"; exit 1; }

bad=0 checked=0
for f in "${files[@]}"; do
    dir=$(dirname "$f")
    # Inline links and images: ](target) outside fenced code blocks and code spans.
    while IFS=: read -r line target; do
        target=${target%% *}                   # drop a title: ](file "title")
        case "$target" in http:*|https:*|mailto:*|'') continue ;; esac
        path=${target%%#*}
        anchor=""
        [[ "$target" == *'#'* ]] && anchor=${target#*#}
        if [ -z "$path" ]; then resolved=$f; else resolved="$dir/$path"; fi
        checked=$((checked + 1))
        if [ ! -e "$resolved" ]; then
            echo "$f:$line: link to '$target': $resolved does not exist"
            bad=$((bad + 1))
        elif [ -n "$anchor" ]; then
            if [ -d "$resolved" ] || ! anchors "$resolved" | grep -qxF -- "$anchor"; then
                echo "$f:$line: link to '$target': no heading with anchor #$anchor in $resolved"
                bad=$((bad + 1))
            fi
        fi
    done < <(awk '/^```/ { fence = !fence; next } !fence { gsub(/`[^`]*`/, ""); print NR ":" $0 }' "$f" |
             grep -o '^[0-9]*:\|\]([^)]*)' | awk '/^[0-9]+:$/ { n = $0; next } { sub(/^\]\(/, ""); sub(/\)$/, ""); print n $0 }')
done
echo "doc_links: ${#files[@]} files, $checked relative links, $bad broken"
[ "$bad" -eq 0 ]
