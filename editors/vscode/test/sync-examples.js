#!/usr/bin/env node
// Copies the repository's example files in the four languages
// (examples/**/*.st, *.stx, *.sfc, *.ld, *.csv) to test/snap/examples/, where
// vscode-tmgrammar-snap reads them and finds their committed .snap beside
// them (the tool writes a .snap next to the file it reads, and examples/ is
// not the editor's to write in). Only the .snap files are committed: each
// holds every line of its example, so the snapshot run itself fails when an
// example no longer matches its snapshot ("source different snapshot at
// line N").
//
//   node test/sync-examples.js          copy; exit 1 if an example has no
//                                       committed .snap (the snapshot tool
//                                       would write one and pass) or a .snap
//                                       has no example any more
//   node test/sync-examples.js --write  copy and drop left-over .snap files
//                                       (`npm run snap:update` runs this, then
//                                       rewrites the snapshots: review the
//                                       diff before committing it)
'use strict';

const fs = require('fs');
const path = require('path');

const here = __dirname;
const examples = path.resolve(here, '..', '..', '..', 'examples');
const copies = path.join(here, 'snap', 'examples');
const EXTENSIONS = ['.st', '.stx', '.sfc', '.ld', '.csv'];
const write = process.argv.includes('--write');

/** Relative paths of the files under `dir` that `keep` accepts. */
function walk(dir, keep, rel = '') {
  if (!fs.existsSync(dir)) return [];
  const out = [];
  for (const entry of fs.readdirSync(dir, { withFileTypes: true })) {
    const r = path.join(rel, entry.name);
    if (entry.isDirectory()) out.push(...walk(path.join(dir, entry.name), keep, r));
    else if (keep(entry.name)) out.push(r);
  }
  return out.sort();
}

const ours = (name) => EXTENSIONS.includes(path.extname(name));
// A ROC host's command list (docs/roc-host.md) is a CSV too, but not an FST
// table: the FST grammar has nothing to say about it.
const commandList = (rel) =>
  rel.endsWith('.csv') && fs.readFileSync(path.join(examples, rel), 'utf8').startsWith('PORT,');
const wanted = walk(examples, ours).filter((rel) => !commandList(rel));
if (wanted.length === 0) {
  console.error(`sync-examples: no example files found under ${examples}`);
  process.exit(1);
}

// The copies: exactly the examples, as they are now.
for (const rel of wanted) {
  const dst = path.join(copies, rel);
  const src = fs.readFileSync(path.join(examples, rel));
  if (!fs.existsSync(dst) || Buffer.compare(src, fs.readFileSync(dst)) !== 0) {
    fs.mkdirSync(path.dirname(dst), { recursive: true });
    fs.writeFileSync(dst, src);
  }
}
for (const rel of walk(copies, ours)) {
  if (!wanted.includes(rel)) fs.rmSync(path.join(copies, rel));
}

const problems = [];
for (const rel of wanted) {
  if (!fs.existsSync(path.join(copies, rel + '.snap'))) {
    problems.push(`examples/${rel} has no snapshot test/snap/examples/${rel}.snap`);
  }
}
for (const snap of walk(copies, (name) => name.endsWith('.snap'))) {
  const source = snap.slice(0, -'.snap'.length);
  if (wanted.includes(source)) continue;
  if (write) {
    fs.rmSync(path.join(copies, snap));
    console.log(`sync-examples: removed test/snap/examples/${snap} (examples/${source} is gone)`);
  } else {
    problems.push(`test/snap/examples/${snap} is left over: examples/${source} is gone`);
  }
}

if (write) {
  console.log(`sync-examples: ${wanted.length} example files copied`);
} else if (problems.length > 0) {
  for (const p of problems) console.error(`sync-examples: ${p}`);
  console.error('sync-examples: run `npm run snap:update` in editors/vscode, review the .snap diff and commit it');
  process.exit(1);
} else {
  console.log(`sync-examples: ${wanted.length} example files copied, each with its snapshot`);
}
