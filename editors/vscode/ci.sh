#!/usr/bin/env bash
# Builds and tests the VS Code extension from a clean tree, with Node and npm
# only: installs the locked dependencies, checks the grammars (snapshots of
# every example file, hand-written scope assertions), tests the extension's
# wiring, packages linc.vsix and checks what the package holds.
set -euo pipefail
cd "$(dirname "$0")"

step() { printf '\n== %s\n' "$*"; }
bin=node_modules/.bin

step "npm ci"
npm ci --no-audit --no-fund

step "copy the examples; each must have its committed snapshot"
node test/sync-examples.js

step "snapshot tests: every example file (examples/**/*.st *.stx *.sfc *.ld *.csv)"
# A missing .snap would be written and pass: sync-examples.js has made sure
# every one exists, so any difference here fails, a changed example too
# (each .snap holds its example's lines).
"$bin/vscode-tmgrammar-snap" 'test/snap/examples/**/*.{st,stx,sfc,ld}'
"$bin/vscode-tmgrammar-snap" --scope source.roc-fst 'test/snap/examples/**/*.csv'

step "assertion tests: test/unit/*.test.*"
"$bin/vscode-tmgrammar-test" 'test/unit/*.test.*'

step "extension and manifest tests (node --test)"
node --test test/extension.test.js test/manifest.test.js

step "package linc.vsix"
rm -f linc.vsix
"$bin/vsce" package --out linc.vsix

step "check linc.vsix"
[ -s linc.vsix ] || { echo "linc.vsix is missing or empty" >&2; exit 1; }
listing=$(unzip -l linc.vsix)
for f in extension/package.json extension/extension.js extension/LICENSE.txt extension/readme.md \
  extension/language-configuration.json extension/fst-language-configuration.json \
  extension/syntaxes/lin-st.tmLanguage.json extension/syntaxes/lin-sfc.tmLanguage.json \
  extension/syntaxes/lin-ladder.tmLanguage.json extension/syntaxes/roc-fst.tmLanguage.json \
  extension/node_modules/vscode-languageclient/package.json; do
  grep -q " $f\$" <<<"$listing" || { echo "linc.vsix lacks $f" >&2; exit 1; }
done
for f in extension/test/ extension/ci.sh extension/node_modules/vscode-tmgrammar-test/ extension/node_modules/@vscode/vsce/; do
  if grep -q " $f" <<<"$listing"; then echo "linc.vsix should not hold $f" >&2; exit 1; fi
done
echo "linc.vsix: $(stat -c %s linc.vsix) bytes, $(grep -c ' extension/' <<<"$listing") files"
