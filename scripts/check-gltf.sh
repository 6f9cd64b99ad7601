#!/usr/bin/env bash
# Checks glTF files strahl exported with the Khronos glTF validator and, with --three,
# photographs each in three.js (headless Chromium) next to the file as <name>.three.png.
#
#   scripts/check-gltf.sh [--three] FILE.glb|FILE.gltf ...
#
# Needs Node.js with npm (the validator and three.js are installed into a temporary folder)
# and, for --three, Debian's chromium. Exits non-zero when a file has validation errors.
set -euo pipefail
three=0
if [[ "${1:-}" == "--three" ]]; then three=1; shift; fi
[[ $# -gt 0 ]] || { echo "usage: $0 [--three] FILE.glb|FILE.gltf ..." >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"; [[ -n "${server:-}" ]] && kill "$server" 2>/dev/null || true' EXIT
(cd "$work" && npm init -y >/dev/null && npm install --silent gltf-validator three@0.170.0 >/dev/null)
cat > "$work/validate.cjs" <<'JS'
const validator = require('gltf-validator');
const fs = require('fs');
const path = require('path');
const file = process.argv[2];
validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
  uri: file,
  externalResourceFunction: (uri) => new Promise((resolve, reject) =>
    fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)),
      (err, data) => err ? reject(err.toString()) : resolve(new Uint8Array(data)))),
}).then((report) => {
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos`);
  for (const m of i.messages.slice(0, 20)) console.log(`  ${m.code} ${m.pointer || ''} ${m.message}`);
  process.exit(i.numErrors > 0 ? 1 : 0);
});
JS
status=0
for f in "$@"; do node "$work/validate.cjs" "$f" || status=1; done
if [[ $three == 1 ]]; then
  # The model is framed from its bounding box, looking along +z as strahl's built-in scenes
  # do; only an ambient light, so what shows is the baked light.
  cat > "$work/index.html" <<'HTML'
<!doctype html><html><body style="margin:0">
<script type="importmap">{"imports":{"three":"./node_modules/three/build/three.module.js",
"three/addons/":"./node_modules/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const renderer = new THREE.WebGLRenderer({preserveDrawingBuffer: true});
renderer.setSize(512, 512);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.add(new THREE.AmbientLight(0xffffff, 1.0));
new GLTFLoader().load('model' + location.hash.slice(1), (g) => {
  scene.add(g.scene);
  const box = new THREE.Box3().setFromObject(g.scene);
  const c = box.getCenter(new THREE.Vector3()), s = box.getSize(new THREE.Vector3());
  const camera = new THREE.PerspectiveCamera(39.3, 1, 0.001 * s.length(), 10 * s.length());
  camera.position.set(c.x, c.y, box.min.z - 1.45 * s.y);
  camera.lookAt(c.x, c.y, c.z);
  renderer.render(scene, camera);
});
</script></body></html>
HTML
  (cd "$work" && python3 -m http.server 8765 >/dev/null 2>&1) & server=$!
  sleep 1
  for f in "$@"; do
    ext="${f##*.}"
    cp "$f" "$work/model.$ext"
    [[ "$ext" == gltf ]] && cp "${f%.*}.bin" "$work/" 2>/dev/null || true
    chromium --headless --no-sandbox --disable-gpu --use-angle=swiftshader \
      --enable-unsafe-swiftshader --disable-quic --no-first-run --disable-background-networking \
      --disable-component-update --disable-sync --user-data-dir="$work/chrome" \
      --window-size=512,512 --virtual-time-budget=10000 \
      --screenshot="${f%.*}.three.png" "http://localhost:8765/index.html#.$ext" 2>/dev/null
    echo "${f%.*}.three.png"
  done
fi
exit $status
