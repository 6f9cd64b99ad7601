// strahl view: the radiosity solution served by `strahl view`, drawn with WebGL2.
// Drag to orbit, shift-drag (or right-drag) to pan, wheel to zoom, arrow keys and
// PageUp/PageDown to walk; a click reads the illuminance where it lands. False colour shows
// the illuminance on the scale `strahl render --false-color` uses (`?false-color` in the
// address starts with it on).
"use strict";

const canvas = document.getElementById("view");
const status = document.getElementById("status");
const reading = document.getElementById("reading");
const gl = canvas.getContext("webgl2", { antialias: true });

const VERTEX = `#version 300 es
in vec3 position;
in vec3 radiance;
in float lux;
uniform mat4 viewProjection;
uniform float scale;
out vec3 colour;
out float illuminance;
void main() {
  colour = radiance * scale;
  illuminance = lux;
  gl_Position = viewProjection * vec4(position, 1.0);
}`;

const FRAGMENT = `#version 300 es
precision highp float;
in vec3 colour;
in float illuminance;
uniform bool lines;
uniform bool falseColour;
uniform vec2 range;
uniform float stopAt[6];
uniform vec3 stopColour[6];
out vec4 result;
// The false-colour scale, in sRGB, at t (0–1).
vec3 scaleColour(float t) {
  t = clamp(t, 0.0, 1.0);
  for (int k = 0; k < 5; k++) {
    if (t <= stopAt[k + 1]) {
      return mix(stopColour[k], stopColour[k + 1], (t - stopAt[k]) / (stopAt[k + 1] - stopAt[k]));
    }
  }
  return stopColour[5];
}
vec3 srgb(vec3 c) {
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
void main() {
  if (lines) {
    result = vec4(0.0, 0.0, 0.0, 1.0);
  } else if (falseColour) {
    result = vec4(scaleColour((illuminance - range.x) / (range.y - range.x)), 1.0);
  } else {
    // Reinhard per channel, then the sRGB curve.
    result = vec4(srgb(colour / (1.0 + colour)), 1.0);
  }
}`;

function shader(type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
  return s;
}

function program() {
  const p = gl.createProgram();
  gl.attachShader(p, shader(gl.VERTEX_SHADER, VERTEX));
  gl.attachShader(p, shader(gl.FRAGMENT_SHADER, FRAGMENT));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  return p;
}

// Vector helpers on plain arrays.
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => mul(a, 1 / Math.hypot(a[0], a[1], a[2]));

// The mesh as `strahl view` sends it (see cli/src/view/server.rs, mesh_bytes).
function parseMesh(buffer) {
  const header = new Uint32Array(buffer, 0, 2);
  const [vertices, triangles] = header;
  const floats = new Float32Array(buffer, 8, vertices * 7);
  const positions = floats.subarray(0, vertices * 3);
  const radiance = floats.subarray(vertices * 3, vertices * 6);
  const lux = floats.subarray(vertices * 6, vertices * 7);
  const indices = new Uint32Array(buffer, 8 + vertices * 28, triangles * 3);
  return { vertices, triangles, positions, radiance, lux, indices };
}

// The exposure that puts the mean luminance of the lit vertices at middle grey.
function autoScale(mesh) {
  let sum = 0, count = 0;
  for (let v = 0; v < mesh.vertices; v++) {
    const r = mesh.radiance;
    const y = 0.2126 * r[3 * v] + 0.7152 * r[3 * v + 1] + 0.0722 * r[3 * v + 2];
    if (y > 0) { sum += y; count++; }
  }
  return count > 0 ? 0.18 / (sum / count) : 1;
}

function edges(indices) {
  const lines = new Uint32Array(indices.length * 2);
  for (let t = 0; t < indices.length; t += 3) {
    for (let k = 0; k < 3; k++) {
      lines[2 * (t + k)] = indices[t + k];
      lines[2 * (t + k) + 1] = indices[t + (k + 1) % 3];
    }
  }
  return lines;
}

// Column-major 4 × 4 matrices.
function perspective(fovY, aspect, near, far) {
  const f = 1 / Math.tan(fovY / 2);
  return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
          0, 0, (2 * far * near) / (near - far), 0];
}

function lookAt(eye, target, up) {
  const z = normalize(sub(eye, target));
  const x = normalize(cross(up, z));
  const y = cross(z, x);
  return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
          -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
}

function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let c = 0; c < 4; c++)
    for (let r = 0; r < 4; r++)
      for (let k = 0; k < 4; k++) out[4 * c + r] += a[4 * k + r] * b[4 * c + k];
  return out;
}

// The orbiting camera: a target, a distance, a yaw and a pitch around the y axis (up).
const view = { target: [0, 0, 0], distance: 1, yaw: 0, pitch: 0, fov: 0.6 };

function eye() {
  const c = Math.cos(view.pitch);
  const offset = [c * Math.sin(view.yaw), Math.sin(view.pitch), c * Math.cos(view.yaw)];
  return add(view.target, mul(offset, view.distance));
}

function startFrom(camera) {
  view.target = camera.look_at;
  const offset = sub(camera.position, camera.look_at);
  view.distance = Math.max(Math.hypot(...offset), 1e-6);
  view.pitch = Math.asin(Math.max(-1, Math.min(1, offset[1] / view.distance)));
  view.yaw = Math.atan2(offset[0], offset[2]);
  view.fov = (camera.fov_degrees * Math.PI) / 180;
}

// The ray through canvas pixel (x, y): origin and unit direction.
function rayThrough(x, y) {
  const e = eye();
  const forward = normalize(sub(view.target, e));
  const right = normalize(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  const t = Math.tan(view.fov / 2);
  const aspect = canvas.width / canvas.height;
  const nx = (2 * (x + 0.5)) / canvas.width - 1;
  const ny = 1 - (2 * (y + 0.5)) / canvas.height;
  return { origin: e, direction: normalize(add(forward, add(mul(right, nx * t * aspect), mul(up, ny * t)))) };
}

async function main() {
  if (!gl) {
    status.textContent = "this browser has no WebGL2";
    return;
  }
  const [scene, buffer] = await Promise.all([
    fetch("/api/scene").then((r) => r.json()),
    fetch("/api/mesh").then((r) => r.arrayBuffer()),
  ]);
  const mesh = parseMesh(buffer);
  document.getElementById("title").textContent = `strahl view — ${scene.name}`;
  status.textContent = `${scene.report.solver}: ${mesh.triangles} triangles; ${scene.summary}`;
  startFrom(scene.camera);

  const prog = program();
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  const attribute = (name, data, size) => {
    const b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    const at = gl.getAttribLocation(prog, name);
    gl.enableVertexAttribArray(at);
    gl.vertexAttribPointer(at, size, gl.FLOAT, false, 0, 0);
  };
  attribute("position", mesh.positions, 3);
  attribute("radiance", mesh.radiance, 3);
  attribute("lux", mesh.lux, 1);
  const triangles = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, triangles);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, mesh.indices, gl.STATIC_DRAW);
  const lineIndices = edges(mesh.indices);
  const lines = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, lines);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, lineIndices, gl.STATIC_DRAW);

  const uniform = (name) => gl.getUniformLocation(prog, name);
  const baseScale = autoScale(mesh);
  const wireframe = document.getElementById("wireframe");
  const exposure = document.getElementById("exposure");
  const falseColour = document.getElementById("false-colour");
  const legend = document.getElementById("legend");
  const scale = scene.false_color;
  falseColour.checked = new URLSearchParams(location.search).has("false-color");
  drawLegend(legend, scale);

  function draw() {
    const dpr = window.devicePixelRatio || 1;
    const [w, h] = [Math.round(canvas.clientWidth * dpr), Math.round(canvas.clientHeight * dpr)];
    if (canvas.width !== w || canvas.height !== h) [canvas.width, canvas.height] = [w, h];
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.13, 0.13, 0.13, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    // Each side of a patch is its own triangle, counter-clockwise from where its light
    // leaves: the side facing away is not drawn (it would fight the near side for depth).
    gl.enable(gl.CULL_FACE);
    gl.useProgram(prog);
    const near = view.distance * 0.01, far = view.distance * 100;
    const matrix = multiply(perspective(view.fov, canvas.width / canvas.height, near, far),
                            lookAt(eye(), view.target, [0, 1, 0]));
    gl.uniformMatrix4fv(uniform("viewProjection"), false, matrix);
    gl.uniform1f(uniform("scale"), baseScale * Math.pow(2, Number(exposure.value)));
    gl.uniform1i(uniform("falseColour"), falseColour.checked ? 1 : 0);
    gl.uniform2f(uniform("range"), scale.range[0], scale.range[1]);
    gl.uniform1fv(uniform("stopAt"), scale.stops.map((s) => s[0]));
    gl.uniform3fv(uniform("stopColour"), scale.stops.flatMap((s) => s[1].map((c) => c / 255)));
    legend.hidden = !falseColour.checked;
    gl.bindVertexArray(vao);
    gl.uniform1i(uniform("lines"), 0);
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, triangles);
    gl.drawElements(gl.TRIANGLES, mesh.indices.length, gl.UNSIGNED_INT, 0);
    if (wireframe.checked) {
      gl.uniform1i(uniform("lines"), 1);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, lines);
      gl.drawElements(gl.LINES, lineIndices.length, gl.UNSIGNED_INT, 0);
    }
  }
  const redraw = () => requestAnimationFrame(draw);
  window.addEventListener("resize", redraw);
  wireframe.addEventListener("change", redraw);
  exposure.addEventListener("input", redraw);
  falseColour.addEventListener("change", redraw);

  let drag = null;
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX, y: e.clientY, moved: 0, pan: e.shiftKey || e.button === 2 };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const [dx, dy] = [e.clientX - drag.x, e.clientY - drag.y];
    drag.moved += Math.abs(dx) + Math.abs(dy);
    [drag.x, drag.y] = [e.clientX, e.clientY];
    if (drag.pan) {
      const forward = normalize(sub(view.target, eye()));
      const right = normalize(cross(forward, [0, 1, 0]));
      const up = cross(right, forward);
      const step = (view.distance * 2 * Math.tan(view.fov / 2)) / canvas.clientHeight;
      view.target = add(view.target, add(mul(right, -dx * step), mul(up, dy * step)));
    } else {
      view.yaw -= dx * 0.01;
      view.pitch = Math.max(-1.5, Math.min(1.5, view.pitch + dy * 0.01));
    }
    redraw();
  });
  canvas.addEventListener("pointerup", async (e) => {
    const clicked = drag && drag.moved < 4;
    drag = null;
    if (!clicked) return;
    const rect = canvas.getBoundingClientRect();
    const dpr = canvas.width / rect.width;
    const ray = rayThrough((e.clientX - rect.left) * dpr, (e.clientY - rect.top) * dpr);
    const query = `o=${ray.origin.join(",")}&d=${ray.direction.join(",")}`;
    const pick = await fetch(`/api/pick?${query}`).then((r) => r.json());
    reading.textContent = describe(pick, scene.report);
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    view.distance *= Math.exp(e.deltaY * 0.001);
    redraw();
  }, { passive: false });
  window.addEventListener("keydown", (e) => {
    const forward = normalize(sub(view.target, eye()));
    const flat = normalize([forward[0], 0, forward[2]]);
    const step = view.distance * 0.05;
    const move = (v) => { view.target = add(view.target, v); };
    switch (e.key) {
      case "ArrowUp": move(mul(flat, step)); break;
      case "ArrowDown": move(mul(flat, -step)); break;
      case "ArrowLeft": view.yaw += 0.05; break;
      case "ArrowRight": view.yaw -= 0.05; break;
      case "PageUp": move([0, step, 0]); break;
      case "PageDown": move([0, -step, 0]); break;
      default: return;
    }
    e.preventDefault();
    redraw();
  });
  redraw();
}

// The legend of the false-colour scale: the unit, a bar from the scale's stops (high end up)
// and the values at five levels.
function drawLegend(legend, scale) {
  const css = (c) => `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
  const bar = document.createElement("div");
  bar.className = "bar";
  bar.style.background = `linear-gradient(to top, ${scale.stops.map((s) => `${css(s[1])} ${100 * s[0]}%`).join(", ")})`;
  const labels = document.createElement("div");
  labels.className = "labels";
  const [low, high] = scale.range;
  for (let k = 4; k >= 0; k--) {
    const label = document.createElement("div");
    label.textContent = String(+(low + ((high - low) * k) / 4).toPrecision(4));
    labels.appendChild(label);
  }
  const unit = document.createElement("div");
  unit.textContent = "lux";
  legend.append(unit, bar, labels);
}

// One pick in words, with the report's row for the object hit.
function describe(pick, report) {
  if (!pick.hit) return "nothing there";
  const row = report.objects.find((o) => o.name === pick.object);
  const lines = [
    `${pick.object}`,
    `here: ${pick.illuminance_lux.toPrecision(4)} lux, ${pick.luminance_cd_m2.toPrecision(4)} cd/m²`,
    `at (${pick.point.map((v) => v.toFixed(3)).join(", ")})`,
  ];
  if (row) {
    if (row.illuminance_lux != null) lines.push(`object mean: ${row.illuminance_lux.toPrecision(4)} lux`);
    const absorbed = row.absorbed_power;
    if (absorbed) lines.push(`absorbed: ${absorbed.map((v) => v.toPrecision(4)).join(" / ")} W (R/G/B)`);
  }
  return lines.join("\n");
}

main().catch((e) => { status.textContent = `error: ${e.message}`; });
