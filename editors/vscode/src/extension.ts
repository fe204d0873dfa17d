// The gaitc extension: starts `gaitc lsp` for .gait files and hands it the editor.
//
// Everything a user sees (errors, hover, completion, rename, fixes, repairs, highlighting of
// names) comes from the language server; this file only starts it, with the command from the
// `gaitc.server.command` setting, and forwards the repair command.

import * as vscode from "vscode";
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
  TransportKind,
} from "vscode-languageclient/node";

let client: LanguageClient | undefined;

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  const configured = vscode.workspace
    .getConfiguration("gaitc")
    .get<string[]>("server.command", ["gaitc", "lsp"]);
  const [command, ...args] = configured.length > 0 ? configured : ["gaitc", "lsp"];
  const serverOptions: ServerOptions = {
    run: { command, args, transport: TransportKind.stdio },
    debug: { command, args, transport: TransportKind.stdio },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [{ scheme: "file", language: "gait" }],
  };
  client = new LanguageClient("gaitc", "gaitc language server", serverOptions, clientOptions);
  context.subscriptions.push(
    vscode.commands.registerCommand("gaitc.findRepairs.active", async () => {
      const editor = vscode.window.activeTextEditor;
      if (editor !== undefined && editor.document.languageId === "gait") {
        await vscode.commands.executeCommand("gaitc.findRepairs", editor.document.uri.toString());
      }
    }),
  );
  await client.start();
}

export async function deactivate(): Promise<void> {
  if (client !== undefined) {
    await client.stop();
  }
}
