#!/usr/bin/env bash
# Build the VS Code extension of gaitc (editors/vscode): install its npm packages from the
# lock file, type-check and bundle it, test its TextMate grammar against the annotated
# specs in editors/vscode/test, and package it. Prints the path of the .vsix.
set -euo pipefail
cd "$(dirname "$0")/../editors/vscode"
if ! command -v npm >/dev/null 2>&1; then
    echo "build-vscode: npm not found; install Node.js and npm (Debian: apt-get install npm)" >&2
    exit 1
fi
npm ci --no-audit --no-fund --loglevel=error >&2
npm run --silent compile >&2
npm run --silent test:grammar >&2
npm run --silent package >&2
echo "$(pwd)/gaitc-gait.vsix"
