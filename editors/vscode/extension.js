// The linc extension: TextMate grammars come from package.json; this file
// starts `linc lsp` (the language server, over stdio) for LIN ST, sequences,
// ladder, FST tables and the strategy database JSON.
'use strict';

const path = require('path');
const vscode = require('vscode');
const { LanguageClient, State } = require('vscode-languageclient/node');

/** @type {LanguageClient | undefined} */
let client;
/** @type {vscode.OutputChannel | undefined} */
let output;
/** @type {vscode.FileSystemWatcher | undefined} */
let jsonWatcher;

/** The documents the server is given: the four languages and database JSON. */
const DOCUMENT_SELECTOR = [
  { scheme: 'file', language: 'lin-st' },
  { scheme: 'file', language: 'lin-sfc' },
  { scheme: 'file', language: 'lin-ladder' },
  { scheme: 'file', language: 'roc-fst' },
  { scheme: 'untitled', language: 'lin-st' },
  { scheme: 'untitled', language: 'lin-sfc' },
  { scheme: 'untitled', language: 'lin-ladder' },
  { scheme: 'untitled', language: 'roc-fst' },
  // The strategy database (docs/database.md) is a JSON file of any name.
  { scheme: 'file', language: 'json', pattern: '**/*.json' },
];

/** `linc.path`, with `~` and `${workspaceFolder}` expanded. */
function lincCommand() {
  const configured = vscode.workspace.getConfiguration('linc').get('path');
  const command = typeof configured === 'string' && configured.trim() !== '' ? configured.trim() : 'linc';
  return expand(command);
}

/**
 * `linc.database`, made absolute against the first workspace folder, or
 * undefined when it is not set.
 */
function databasePath() {
  const configured = vscode.workspace.getConfiguration('linc').get('database');
  if (typeof configured !== 'string' || configured.trim() === '') return undefined;
  const p = expand(configured.trim());
  if (path.isAbsolute(p)) return p;
  const folder = vscode.workspace.workspaceFolders && vscode.workspace.workspaceFolders[0];
  return folder ? path.join(folder.uri.fsPath, p) : p;
}

function expand(p) {
  const folder = vscode.workspace.workspaceFolders && vscode.workspace.workspaceFolders[0];
  let out = p;
  if (folder) out = out.split('${workspaceFolder}').join(folder.uri.fsPath);
  if (out === '~' || out.startsWith('~/')) {
    const home = process.env.HOME || process.env.USERPROFILE;
    if (home) out = path.join(home, out.slice(1));
  }
  return out;
}

function createClient() {
  const command = lincCommand();
  // No `transport` field: with TransportKind.stdio the client would append
  // `--stdio` to the arguments. Left out, it talks over stdin/stdout all
  // the same, and runs exactly `linc lsp`.
  const serverOptions = {
    run: { command, args: ['lsp'] },
    debug: { command, args: ['lsp'] },
  };
  const initializationOptions = {};
  const database = databasePath();
  if (database !== undefined) initializationOptions.database = database;

  const clientOptions = {
    documentSelector: DOCUMENT_SELECTOR,
    initializationOptions,
    outputChannel: output,
    // Database JSON files of the workspace change the diagnostics of every
    // program that uses them.
    synchronize: jsonWatcher ? { fileEvents: jsonWatcher } : undefined,
  };
  // The id `linc` makes the client read the `linc.trace.server` setting.
  return new LanguageClient('linc', 'linc', serverOptions, clientOptions);
}

async function startClient() {
  client = createClient();
  try {
    await client.start();
  } catch (err) {
    const message = err && err.message ? err.message : String(err);
    const choice = await vscode.window.showErrorMessage(
      `linc: could not start the language server (\`${lincCommand()} lsp\`): ${message}. ` +
        'Put linc on PATH or set `linc.path` to the linc executable.',
      'Open Settings',
      'Show Output',
    );
    if (choice === 'Open Settings') {
      vscode.commands.executeCommand('workbench.action.openSettings', 'linc.path');
    } else if (choice === 'Show Output' && output) {
      output.show(true);
    }
  }
}

async function stopClient() {
  const c = client;
  client = undefined;
  if (c && c.state !== State.Stopped) {
    try {
      await c.stop();
    } catch (_) {
      // A server that never started (or already died) has nothing to stop.
    }
  }
}

async function restart() {
  await stopClient();
  await startClient();
}

/** @param {vscode.ExtensionContext} context */
async function activate(context) {
  output = vscode.window.createOutputChannel('linc');
  context.subscriptions.push(output);
  jsonWatcher = vscode.workspace.createFileSystemWatcher('**/*.json');
  context.subscriptions.push(jsonWatcher);
  context.subscriptions.push(vscode.commands.registerCommand('linc.restartServer', restart));
  context.subscriptions.push(
    vscode.workspace.onDidChangeConfiguration((e) => {
      if (e.affectsConfiguration('linc.path') || e.affectsConfiguration('linc.database')) {
        restart();
      }
    }),
  );
  await startClient();
}

function deactivate() {
  return stopClient();
}

module.exports = { activate, deactivate };
