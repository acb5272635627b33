// package.json and the language configurations: what VS Code reads without
// running anything (language ids, grammar files, the FST first-line rule,
// folding and indentation regexes).
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const fs = require('fs');
const path = require('path');

const root = path.join(__dirname, '..');
const pkg = JSON.parse(fs.readFileSync(path.join(root, 'package.json'), 'utf8'));
const examples = path.join(root, '..', '..', 'examples');

test('four languages, each with its grammar and configuration', () => {
  const ids = pkg.contributes.languages.map((l) => l.id);
  assert.deepStrictEqual(ids, ['lin-st', 'lin-sfc', 'lin-ladder', 'roc-fst']);
  for (const lang of pkg.contributes.languages) {
    const grammar = pkg.contributes.grammars.find((g) => g.language === lang.id);
    assert.ok(grammar, `grammar for ${lang.id}`);
    const g = JSON.parse(fs.readFileSync(path.join(root, grammar.path), 'utf8'));
    assert.strictEqual(g.scopeName, grammar.scopeName);
    assert.strictEqual(grammar.scopeName, `source.${lang.id}`);
    JSON.parse(fs.readFileSync(path.join(root, lang.configuration), 'utf8'));
    assert.ok(pkg.activationEvents.includes(`onLanguage:${lang.id}`));
  }
});

test('grammars include only grammars the package contributes', () => {
  const scopes = new Set(pkg.contributes.grammars.map((g) => g.scopeName));
  for (const g of pkg.contributes.grammars) {
    const text = fs.readFileSync(path.join(root, g.path), 'utf8');
    for (const m of text.matchAll(/"include":\s*"([^"#$][^"#]*)/g)) {
      assert.ok(scopes.has(m[1]), `${g.path} includes ${m[1]}`);
    }
  }
});

test('FST tables are recognised by their header, not by .csv', () => {
  const fst = pkg.contributes.languages.find((l) => l.id === 'roc-fst');
  assert.strictEqual(fst.extensions, undefined, 'no claim on every .csv');
  assert.deepStrictEqual(fst.filenamePatterns, ['*.fst.csv']);
  const firstLine = new RegExp(fst.firstLine);
  const tables = fs.readdirSync(path.join(examples, 'fst')).filter((f) => f.endsWith('.csv'));
  assert.ok(tables.length > 0);
  for (const t of tables) {
    const header = fs.readFileSync(path.join(examples, 'fst', t), 'utf8').split(/\r?\n/)[0];
    assert.match(header, firstLine, t);
  }
  assert.match('\uFEFF step ; Label;cmd;ARGUMENT 1;Argument 2', firstLine);
  assert.doesNotMatch('name,value,unit', firstLine);
  assert.doesNotMatch('0,,VAL,1,,', firstLine);
});

test('the settings the extension reads are contributed', () => {
  const props = pkg.contributes.configuration.properties;
  assert.strictEqual(props['linc.path'].default, 'linc');
  assert.ok(props['linc.database']);
  assert.deepStrictEqual(props['linc.trace.server'].enum, ['off', 'messages', 'verbose']);
  assert.ok(pkg.contributes.commands.some((c) => c.command === 'linc.restartServer'));
});

const config = JSON.parse(fs.readFileSync(path.join(root, 'language-configuration.json'), 'utf8'));
const re = (o) => new RegExp(o.pattern, o.flags);

test('comments and brackets', () => {
  assert.deepStrictEqual(config.comments.blockComment, ['(*', '*)']);
  assert.strictEqual(config.comments.lineComment, undefined);
  const closes = config.autoClosingPairs.map((p) => p.open);
  for (const open of ['(', '[', '{', "'", '"']) assert.ok(closes.includes(open), open);
});

test('folding: blocks fold, one-liners do not open a fold', () => {
  const start = re(config.folding.markers.start);
  const end = re(config.folding.markers.end);
  for (const line of ['IF x THEN', '    if x then', 'FOR i := 1 TO 3 DO', 'While x Do', 'REPEAT', 'STEP Fill:', 'INITIAL_STEP Idle:',
    'TRANSITION Full FROM a TO b', 'ACTION Stir : CHART', '(* a comment']) {
    assert.match(line, start, line);
  }
  for (const line of ['IF x THEN y := 1; END_IF;', 'STEP Fill: FillOn(N); END_STEP', 'TRANSITION FROM a TO b := c; END_TRANSITION',
    '(* closed *)', 'IF_X := 1;', 'x := 1;']) {
    assert.doesNotMatch(line, start, line);
  }
  for (const line of ['END_IF;', 'end_for;', 'END_WHILE;', 'END_REPEAT;', 'END_STEP', 'END_TRANSITION', 'END_ACTION', '   lines *)']) {
    assert.match(line, end, line);
  }
  assert.doesNotMatch('x := 1; (* c *)', end);
});

test('indentation: in after THEN/DO/ELSE/REPEAT/ACTION, out on END_*/ELSE/ELSIF/UNTIL', () => {
  const inc = re(config.indentationRules.increaseIndentPattern);
  const dec = re(config.indentationRules.decreaseIndentPattern);
  for (const line of ['IF a THEN', 'ELSIF b then', 'else', 'FOR i := 0 TO 6 DO', 'WHILE x DO (* loop *)', 'REPEAT', 'ACTION Fill',
    'STEP Fill:', 'TRANSITION FROM a TO b']) {
    assert.match(line, inc, line);
  }
  for (const line of ['x := 1;', 'IF a THEN b := 1; END_IF;', 'STEP Fill: FillOn(N); END_STEP', 'END_IF;']) {
    assert.doesNotMatch(line, inc, line);
  }
  for (const line of ['END_IF;', '  end_while;', 'ELSE', 'ELSIF x THEN', 'UNTIL x', 'END_ACTION', 'END_STEP']) {
    assert.match(line, dec, line);
  }
  for (const line of ['ELSEWHERE := 1;', 'x := END_X;']) assert.doesNotMatch(line, dec, line);
});
