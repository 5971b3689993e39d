# Shared by the lessons' picture scripts (sourced, not run): a scratch folder $TMP removed on exit,
# the working directory at the project root $ROOT (set by the caller), and `engine ARGS…`: the engine,
# $OPENGL3D when set (an already-built binary), else `cargo run --release --` after one build.
# `run` is `engine` unless the caller redefines it (e.g. to silence the renders).

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
cd "$ROOT"

if [ -n "${OPENGL3D:-}" ]; then
  engine() { "$OPENGL3D" "$@"; }
else
  cargo build --release
  engine() { cargo run --release --quiet -- "$@"; }
fi
run() { engine "$@"; }
