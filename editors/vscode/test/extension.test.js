// extension.js without VS Code: `vscode` and the language client are
// replaced by recording fakes, so the test checks what the extension asks
// for — `linc lsp` with the configured path, the documents, the database
// initialization option, the restart command — not the client library.
'use strict';

const test = require('node:test');
const assert = require('node:assert');
const Module = require('module');
const path = require('path');

function load({ settings = {}, folder = '/work/plant', startFails = false } = {}) {
  const created = [];
  const commands = {};
  const errors = [];
  let configListener;
  const vscode = {
    workspace: {
      workspaceFolders: folder ? [{ uri: { fsPath: folder } }] : undefined,
      getConfiguration: (section) => ({ get: (key) => settings[`${section}.${key}`] }),
      createFileSystemWatcher: (glob) => ({ glob, dispose() {} }),
      onDidChangeConfiguration: (fn) => {
        configListener = fn;
        return { dispose() {} };
      },
    },
    window: {
      createOutputChannel: (name) => ({ name, show() {}, dispose() {} }),
      showErrorMessage: async (msg) => {
        errors.push(msg);
        return undefined;
      },
    },
    commands: {
      registerCommand: (id, fn) => {
        commands[id] = fn;
        return { dispose() {} };
      },
      executeCommand: async () => {},
    },
  };
  class LanguageClient {
    constructor(id, name, serverOptions, clientOptions) {
      Object.assign(this, { id, name, serverOptions, clientOptions, state: 1, starts: 0, stops: 0 });
      created.push(this);
    }
    async start() {
      this.starts += 1;
      if (startFails) throw new Error('spawn linc ENOENT');
      this.state = 2;
    }
    async stop() {
      this.stops += 1;
      this.state = 1;
    }
  }
  const fakes = { vscode, 'vscode-languageclient/node': { LanguageClient, State: { Stopped: 1, Running: 2 } } };
  const original = Module._load;
  Module._load = function (request, parent, isMain) {
    if (Object.prototype.hasOwnProperty.call(fakes, request)) return fakes[request];
    return original.call(this, request, parent, isMain);
  };
  const file = path.join(__dirname, '..', 'extension.js');
  delete require.cache[require.resolve(file)];
  try {
    return { ext: require(file), created, commands, errors, changeConfig: (keys) => configListener({ affectsConfiguration: (k) => keys.includes(k) }) };
  } finally {
    Module._load = original;
  }
}

const context = () => ({ subscriptions: [] });

test('starts `linc lsp` over stdio with the default path', async () => {
  const { ext, created } = load();
  await ext.activate(context());
  assert.strictEqual(created.length, 1);
  const c = created[0];
  assert.strictEqual(c.id, 'linc', 'the id makes the client read linc.trace.server');
  assert.deepStrictEqual(c.serverOptions.run, { command: 'linc', args: ['lsp'] });
  assert.deepStrictEqual(c.serverOptions.debug, { command: 'linc', args: ['lsp'] });
  assert.strictEqual(c.serverOptions.run.transport, undefined, 'TransportKind.stdio would add --stdio');
  assert.strictEqual(c.starts, 1);
});

test('serves the four languages and database JSON', async () => {
  const { ext, created } = load();
  await ext.activate(context());
  const selector = created[0].clientOptions.documentSelector;
  for (const language of ['lin-st', 'lin-sfc', 'lin-ladder', 'roc-fst']) {
    assert.ok(selector.some((s) => s.language === language && s.scheme === 'file'), language);
  }
  assert.ok(selector.some((s) => s.language === 'json' && s.pattern === '**/*.json'));
});

test('linc.path and linc.database reach the server', async () => {
  const { ext, created } = load({
    settings: { 'linc.path': '${workspaceFolder}/target/release/linc', 'linc.database': 'examples/strategy/plant.json' },
  });
  await ext.activate(context());
  const c = created[0];
  assert.strictEqual(c.serverOptions.run.command, '/work/plant/target/release/linc');
  assert.deepStrictEqual(c.clientOptions.initializationOptions, { database: '/work/plant/examples/strategy/plant.json' });
});

test('no database option when linc.database is not set', async () => {
  const { ext, created } = load({ settings: { 'linc.database': '' } });
  await ext.activate(context());
  assert.deepStrictEqual(created[0].clientOptions.initializationOptions, {});
});

test('linc.restartServer stops the client and starts a new one', async () => {
  const { ext, created, commands } = load();
  await ext.activate(context());
  assert.ok(commands['linc.restartServer']);
  await commands['linc.restartServer']();
  assert.strictEqual(created.length, 2);
  assert.strictEqual(created[0].stops, 1);
  assert.strictEqual(created[1].starts, 1);
});

test('changing linc.path restarts the server', async () => {
  const { ext, created, changeConfig } = load();
  await ext.activate(context());
  changeConfig(['linc.path']);
  await new Promise((r) => setImmediate(r));
  assert.strictEqual(created.length, 2);
  changeConfig(['editor.fontSize']);
  await new Promise((r) => setImmediate(r));
  assert.strictEqual(created.length, 2);
});

test('a missing linc is reported, naming linc.path', async () => {
  const { ext, errors } = load({ startFails: true });
  await ext.activate(context());
  assert.strictEqual(errors.length, 1);
  assert.match(errors[0], /linc\.path/);
  assert.match(errors[0], /linc lsp/);
  await ext.deactivate();
});
