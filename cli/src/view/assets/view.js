// strahl view: the radiosity solution served by `strahl view`, drawn with WebGL2, redrawn
// whenever the server has a newer one (a preview, then the final solution, after a move).
// Drag to orbit, shift-drag (or right-drag) to pan, wheel to zoom, arrow keys and
// PageUp/PageDown to walk; a click reads the illuminance where it lands. Textured surfaces
// show their textures lit by the solution (lightmaps baked by the server), and every
// surface goes through the tone mapping `strahl render --tonemap` names, over the mesh's
// luminances. False colour shows the illuminance on the scale `strahl render --false-color`
// uses.
//
// The address may ask for a view and for actions once the first final solution is drawn:
// `?false-color` (with `&range=MIN,MAX` in lux and `&isolines=N`), `?wireframe`, `?links`
// (all links) or `?links=picked` start with those on, `&level=N` only the links of level N
// (−1: those with a cluster at an end; `lights`: those from lamps, the sun and the sky);
// `?tonemap=linear|log|reinhard|auto` and `&exposure=EV` choose the tone mapping
// (automatic exposure unless asked), `?textures=off` shows textured surfaces by their
// corners' radiance instead of their lightmaps; `?move=NAME:X,Y,Z` moves an object or light by the offset; `?pick=X,Y` then reads the
// surface at that point of the final solution (X, Y: fractions of the view's width and
// height from its top left corner); `?orbit=N` draws N frames
// turning round the target and shows the frame times; `?still` stops listening for newer
// solutions once these are done (for scripted screenshots: the page then goes quiet).
"use strict";

const canvas = document.getElementById("view");
const status = document.getElementById("status");
const reading = document.getElementById("reading");
const timing = document.getElementById("timing");
const params = new URLSearchParams(location.search);
const gl = canvas.getContext("webgl2", { antialias: true });

const VERTEX = `#version 300 es
in vec3 position;
in vec3 radiance;
in float lux;
in vec2 lightmapAt;
in vec2 materialAt;
uniform mat4 viewProjection;
out vec3 vertexRadiance;
out float illuminance;
out vec2 texel;
out vec2 materialTexel;
void main() {
  vertexRadiance = radiance;
  illuminance = lux;
  texel = lightmapAt;
  materialTexel = materialAt;
  gl_Position = viewProjection * vec4(position, 1.0);
  gl_PointSize = 9.0;
}`;

const FRAGMENT = `#version 300 es
precision highp float;
in vec3 vertexRadiance;
in float illuminance;
in vec2 texel;
in vec2 materialTexel;
uniform bool lines;
uniform bool textured;
uniform sampler2D lightmap;
// A surface cut by its material's alpha texture: the mask (1 present, 0 cut away, nearest
// texel, as strahl's ray queries test it) at the material's texture coordinates.
uniform bool cut;
uniform sampler2D mask;
// The tone mapping (0 linear, 1 logarithmic, 2 Reinhard, 3 automatic exposure, as
// strahl render --tonemap defines them), the radiance scale it applies (2^EV, times
// 0.18 over the log-average luminance for 2 and 3) and, for 1, ln(1 + Lmax·scale).
uniform int toneMap;
uniform float scale;
uniform float logDenominator;
uniform vec4 lineColour;
uniform bool falseColour;
uniform vec2 range;
uniform int isolines;
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
// Display-linear colour (0–1) of radiance c.
vec3 toneMapped(vec3 c) {
  float l = dot(c, vec3(0.2126, 0.7152, 0.0722));
  if (toneMap == 1 || toneMap == 2) {
    if (!(l > 0.0)) return vec3(0.0);
    float s = l * scale;
    float mapped = toneMap == 1 ? log(1.0 + s) / logDenominator : s / (1.0 + s);
    return clamp(c * (mapped / l), 0.0, 1.0);
  }
  return clamp(c * scale, 0.0, 1.0);
}
vec3 srgb(vec3 c) {
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
void main() {
  if (cut && !lines && texture(mask, materialTexel).r < 0.5) discard;
  if (lines) {
    result = lineColour;
  } else if (falseColour) {
    float t = (illuminance - range.x) / (range.y - range.x);
    vec3 c = scaleColour(t);
    if (isolines > 0) {
      // A dark line where the illuminance crosses one of the levels, a pixel or so wide.
      float level = t * float(isolines);
      float near = abs(fract(level + 0.5) - 0.5) / max(fwidth(level), 1e-6);
      if (level > 0.5 && level < float(isolines) + 0.5) c *= mix(0.15, 1.0, smoothstep(0.5, 1.5, near));
    }
    result = vec4(c, 1.0);
  } else {
    // A textured surface shows its lightmap (the texture lit by the solution), every other
    // its corners' radiance.
    vec3 radiance = textured ? texture(lightmap, texel).rgb : vertexRadiance;
    result = vec4(srgb(toneMapped(radiance)), 1.0);
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

// The mesh as `strahl view` sends it (see cli/src/view/snapshot.rs, mesh_bytes).
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

// The lightmaps as `strahl view` sends them (cli/src/view/snapshot.rs, lightmap_bytes), for
// `mesh`: null when there are none or they belong to another solution than the mesh.
function parseLightmaps(buffer, mesh) {
  const data = new DataView(buffer);
  const surfaces = data.getUint32(0, true);
  if (surfaces === 0) return null;
  const [vertices, triangles] = [data.getUint32(4, true), data.getUint32(8, true)];
  if (vertices !== mesh.vertices || triangles !== mesh.triangles) return null;
  let at = 12;
  const uv = new Float32Array(buffer.slice(at, at + 8 * vertices));
  at += 8 * vertices;
  const surfaceOf = new Int32Array(buffer.slice(at, at + 4 * triangles));
  at += 4 * triangles;
  const maps = [];
  for (let k = 0; k < surfaces; k++) {
    const [width, height] = [data.getUint32(at, true), data.getUint32(at + 4, true)];
    at += 8;
    maps.push({ width, height, texels: new Float32Array(buffer.slice(at, at + 12 * width * height)) });
    at += 12 * width * height;
  }
  // The cut-outs: the material's texture coordinates, each surface's mask (−1: none), the
  // masks.
  const materialUv = new Float32Array(buffer.slice(at, at + 8 * vertices));
  at += 8 * vertices;
  const maskOf = new Int32Array(buffer.slice(at, at + 4 * surfaces));
  at += 4 * surfaces;
  const maskCount = data.getUint32(at, true);
  at += 4;
  const masks = [];
  for (let k = 0; k < maskCount; k++) {
    const [width, height, clamp] = [0, 4, 8].map((o) => data.getUint32(at + o, true));
    at += 12;
    masks.push({ width, height, clamp: clamp === 1, present: new Uint8Array(buffer.slice(at, at + width * height)) });
    at += width * height;
  }
  return { uv, surfaceOf, maps, materialUv, maskOf, masks };
}

// What the tone mappings need of `mesh`: the log-average of the vertices' positive
// luminances, each weighted by the area it stands for (a third of its triangles'), and the
// largest luminance; as `strahl render --tonemap` takes them over an image's pixels.
function luminanceStatistics(mesh) {
  const weight = new Float64Array(mesh.vertices);
  const p = mesh.positions, ix = mesh.indices;
  for (let t = 0; t < ix.length; t += 3) {
    const [a, b, c] = [ix[t], ix[t + 1], ix[t + 2]].map((v) => [p[3 * v], p[3 * v + 1], p[3 * v + 2]]);
    const n = cross(sub(b, a), sub(c, a));
    const third = Math.hypot(n[0], n[1], n[2]) / 6;
    for (const v of [ix[t], ix[t + 1], ix[t + 2]]) weight[v] += third;
  }
  let sum = 0, total = 0, max = 0;
  const r = mesh.radiance;
  for (let v = 0; v < mesh.vertices; v++) {
    const y = 0.2126 * r[3 * v] + 0.7152 * r[3 * v + 1] + 0.0722 * r[3 * v + 2];
    if (!(y > 0) || !Number.isFinite(y)) continue;
    max = Math.max(max, y);
    if (weight[v] > 0) { sum += weight[v] * Math.log(y); total += weight[v]; }
  }
  return { logAverage: total > 0 ? Math.exp(sum / total) : 0, max };
}

// The tone mapping chosen, as the shader takes it: its number, radiance scale and the
// logarithmic mapping's denominator (see FRAGMENT).
const TONE_MAPS = ["linear", "log", "reinhard", "auto"];
function toneUniforms() {
  const { logAverage, max } = shown.luminance;
  const operator = Math.max(0, TONE_MAPS.indexOf(control("tonemap").value));
  const exposure = Math.pow(2, Number(control("exposure").value));
  const keyed = operator >= 2 ? (logAverage > 0 ? 0.18 / logAverage : 0) : 1;
  const scale = keyed * exposure;
  return { operator, scale, logDenominator: Math.log1p(max * scale) || 1 };
}

// The links as `strahl view` sends them (cli/src/view/snapshot.rs, link_bytes): end points
// (receiver, emitter), the objects at their ends (−1: a cluster or a light), the level (the
// quadtree depth of the finer end; −1: a cluster at an end) and the light a link brings
// (−1: none; its emitter end is then the lamp, or toward the sun or the sky).
function parseLinks(buffer) {
  const count = new Uint32Array(buffer, 0, 1)[0];
  const positions = new Float32Array(count * 6);
  const objects = new Int32Array(count * 2);
  const levels = new Int32Array(count);
  const lights = new Int32Array(count);
  const data = new DataView(buffer, 4);
  const size = 40;
  for (let k = 0; k < count; k++) {
    for (let j = 0; j < 6; j++) positions[6 * k + j] = data.getFloat32(size * k + 4 * j, true);
    objects[2 * k] = data.getInt32(size * k + 24, true);
    objects[2 * k + 1] = data.getInt32(size * k + 28, true);
    levels[k] = data.getInt32(size * k + 32, true);
    lights[k] = data.getInt32(size * k + 36, true);
  }
  return { count, positions, objects, levels, lights };
}

// The level selector's choices: every level the links have, clusters (−1) first.
function offerLevels(links) {
  const select = control("links-level");
  // Until links came, the selector holds only "every level": then the address chooses.
  const wanted = select.options.length > 1 ? select.value : params.get("level") || "all";
  const present = [...new Set(links.levels)].sort((a, b) => a - b);
  const lit = links.lights.some((l) => l >= 0) ? ["lights"] : [];
  select.replaceChildren(...["all", ...lit, ...present.map(String)].map((value) => {
    const option = document.createElement("option");
    option.value = value;
    option.textContent = value === "all" ? "every level"
      : value === "lights" ? "from lamps, sun and sky"
      : value === "-1" ? "clusters" : `level ${value}`;
    return option;
  }));
  select.value = [...select.options].some((o) => o.value === wanted) ? wanted : "all";
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

const fetchOk = async (url, options) => {
  const r = await fetch(url, options);
  if (!r.ok) throw new Error(`${url}: ${r.status} ${await r.text()}`);
  return r;
};

// What is drawn: the latest solution loaded, its GPU buffers and the links.
const shown = {
  scene: null, report: null, mesh: null, lightmaps: null, links: null, picked: -1, version: 0, meshVersion: 0,
  luminance: { logAverage: 0, max: 0 },
};
let prog, vao, linkVao, triangleBuffer, lineBuffer, lineCount = 0, linkIndexBuffer, linkCount = 0;
let sensorVao, sensorCount = 0;
// The triangles by what shows them: `{ surface, start, count }` in the triangle buffer
// (surface −1: their corners' radiance; else that lightmap, `textures[surface]`).
let triangleGroups = [], textures = [], masks = [];
const control = (id) => document.getElementById(id);

// Shows a solution: its scene description (`scene`, parsed) with its mesh and lightmaps
// where they are new (`meshBytes`, `lightmapBytes`; null: a solution whose report alone is
// new, the final gather's after the final solve was shown, keeps the mesh, lightmaps and
// links drawn), then its links where they are shown; resolves to `scene`.
async function load(scene, meshBytes, lightmapBytes) {
  const first = shown.scene === null;
  // Between rounds there is no report: picks read the latest whole solution and its report.
  const report = scene.report || shown.report;
  Object.assign(shown, { scene, version: scene.version, report });
  if (meshBytes) {
    const mesh = parseMesh(meshBytes);
    const lightmaps = parseLightmaps(lightmapBytes, mesh);
    Object.assign(shown, { mesh, lightmaps, links: null, meshVersion: scene.mesh_version });
    // The tone mapping's statistics come from the latest whole solution (the flat ones
    // between rounds would change the exposure as the solve goes on).
    if (scene.stage !== "round" || shown.luminance.max === 0) shown.luminance = luminanceStatistics(mesh);
    upload();
  }
  if (first) {
    document.getElementById("title").textContent = `strahl view — ${scene.name}`;
    startFrom(scene.camera);
    fillMovable(scene.movable);
  }
  drawLegend(control("legend"), scene.false_color.stops, falseRange(), isolineCount());
  listSensors(shown.report);
  describeSolution();
  draw();
  // Drawn to the end before the next request goes out (and before a move's timing reads
  // the clock).
  gl.finish();
  if ((control("links").checked || params.has("links")) && !shown.links) {
    await fetchLinks();
    uploadLinks();
    describeSolution();
    draw();
  }
  return scene;
}

// The links of the solution shown (fetched only while they are shown). A 409: a newer
// solution came meanwhile, and its links come with it when it is loaded.
async function fetchLinks() {
  const r = await fetch(`/api/links?mesh=${shown.meshVersion}`);
  if (r.status === 409) return;
  if (!r.ok) throw new Error(`/api/links: ${r.status} ${await r.text()}`);
  shown.links = parseLinks(await r.arrayBuffer());
  offerLevels(shown.links);
}

// The solution's GPU buffers.
function upload() {
  const { mesh } = shown;
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
  const { lightmaps } = shown;
  attribute("lightmapAt", lightmaps ? lightmaps.uv : new Float32Array(2 * mesh.vertices), 2);
  attribute("materialAt", lightmaps ? lightmaps.materialUv : new Float32Array(2 * mesh.vertices), 2);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, triangleBuffer);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, groupedTriangles(mesh, lightmaps), gl.STATIC_DRAW);
  uploadTextures(lightmaps);
  const lineIndices = edges(mesh.indices);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, lineBuffer);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, lineIndices, gl.STATIC_DRAW);
  lineCount = lineIndices.length;
  uploadLinks();
  uploadSensors();
}

// The triangle indices ordered by what shows them (see `triangleGroups`).
function groupedTriangles(mesh, lightmaps) {
  if (!lightmaps) {
    triangleGroups = [{ surface: -1, start: 0, count: mesh.indices.length }];
    return mesh.indices;
  }
  const order = [...Array(mesh.triangles).keys()];
  order.sort((a, b) => lightmaps.surfaceOf[a] - lightmaps.surfaceOf[b] || a - b);
  const indices = new Uint32Array(mesh.indices.length);
  triangleGroups = [];
  order.forEach((t, k) => {
    indices.set(mesh.indices.subarray(3 * t, 3 * t + 3), 3 * k);
    const surface = lightmaps.surfaceOf[t];
    const last = triangleGroups[triangleGroups.length - 1];
    if (last && last.surface === surface) last.count += 3;
    else triangleGroups.push({ surface, start: 3 * k, count: 3 });
  });
  return indices;
}

// The lightmaps as textures: linear radiance in half floats (filterable in WebGL2).
function uploadTextures(lightmaps) {
  textures.forEach((t) => gl.deleteTexture(t));
  textures = (lightmaps ? lightmaps.maps : []).map((map) => {
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGB16F, map.width, map.height, 0, gl.RGB, gl.FLOAT, map.texels);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    return t;
  });
  // The cut-out masks: a byte a texel, 255 where the surface is present.
  masks.forEach((t) => gl.deleteTexture(t));
  masks = (lightmaps ? lightmaps.masks : []).map((mask) => {
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    const present = mask.present.map((p) => 255 * p);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R8, mask.width, mask.height, 0, gl.RED, gl.UNSIGNED_BYTE, present);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    const wrap = mask.clamp ? gl.CLAMP_TO_EDGE : gl.REPEAT;
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, wrap);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, wrap);
    return t;
  });
}

// The sensors of the latest report, as points.
function uploadSensors() {
  const sensors = (shown.report && shown.report.sensors) || [];
  sensorCount = sensors.length;
  if (sensorCount === 0) return;
  gl.bindVertexArray(sensorVao);
  const b = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, b);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(sensors.flatMap((r) => r.position)), gl.STATIC_DRAW);
  const at = gl.getAttribLocation(prog, "position");
  gl.enableVertexAttribArray(at);
  gl.vertexAttribPointer(at, 3, gl.FLOAT, false, 0, 0);
}

// The links to draw: all, or those of the object picked last.
function uploadLinks() {
  const { links } = shown;
  linkCount = 0;
  if (!links) return;
  gl.bindVertexArray(linkVao);
  const b = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, b);
  gl.bufferData(gl.ARRAY_BUFFER, links.positions, gl.STATIC_DRAW);
  const at = gl.getAttribLocation(prog, "position");
  gl.enableVertexAttribArray(at);
  gl.vertexAttribPointer(at, 3, gl.FLOAT, false, 0, 0);
  const onlyPicked = control("links-picked").checked;
  const level = control("links-level").value;
  const chosen = [];
  for (let k = 0; k < links.count; k++) {
    const [r, e] = [links.objects[2 * k], links.objects[2 * k + 1]];
    const ofLevel = level === "all" || level === ""
      || (level === "lights" ? links.lights[k] >= 0 : links.levels[k] === Number(level));
    if (ofLevel && (!onlyPicked || r === shown.picked || e === shown.picked)) chosen.push(2 * k, 2 * k + 1);
  }
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, linkIndexBuffer);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint32Array(chosen), gl.STATIC_DRAW);
  linkCount = chosen.length;
}

function describeSolution() {
  const { scene, mesh, links } = shown;
  const linkText = links ? `; ${linkCount / 2} of ${scene.links[1]} links shown` : "";
  const stage = scene.stage === "solved" ? "final solution, its report being gathered" : `${scene.stage} solution`;
  const what = scene.stage === "round" ? "solving, flat between rounds" : `${scene.report.solver}, ${stage}`;
  status.textContent = `${what}: ${mesh.triangles} triangles${linkText}; ${scene.summary}`;
  status.dataset.version = scene.version;
  status.dataset.stage = scene.stage;
  status.dataset.moves = scene.moves;
}

function uniform(name) { return gl.getUniformLocation(prog, name); }

// The false-colour range (lux): what the two fields say, else the solution's own.
function falseRange() {
  const [low, high] = shown.scene.false_color.range;
  const typed = (id, fallback) => {
    const v = control(id).value.trim();
    return v === "" || !Number.isFinite(Number(v)) ? fallback : Number(v);
  };
  const range = [typed("range-min", low), typed("range-max", high)];
  return range[1] > range[0] ? range : [low, high];
}

// Isolines asked for (0–20).
function isolineCount() {
  return Math.max(0, Math.min(20, Math.round(Number(control("isolines").value) || 0)));
}

function draw() {
  if (!shown.mesh) return;
  const scale = shown.scene.false_color;
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
  const tone = toneUniforms();
  gl.uniform1i(uniform("toneMap"), tone.operator);
  gl.uniform1f(uniform("scale"), tone.scale);
  gl.uniform1f(uniform("logDenominator"), tone.logDenominator);
  gl.uniform1i(uniform("lightmap"), 0);
  gl.uniform1i(uniform("mask"), 1);
  const falseColour = control("false-colour").checked;
  gl.uniform1i(uniform("falseColour"), falseColour ? 1 : 0);
  const range = falseRange();
  gl.uniform2f(uniform("range"), range[0], range[1]);
  gl.uniform1i(uniform("isolines"), isolineCount());
  gl.uniform1fv(uniform("stopAt"), scale.stops.map((s) => s[0]));
  gl.uniform3fv(uniform("stopColour"), scale.stops.flatMap((s) => s[1].map((c) => c / 255)));
  control("legend").hidden = !falseColour;
  gl.bindVertexArray(vao);
  gl.uniform1i(uniform("lines"), 0);
  gl.enable(gl.POLYGON_OFFSET_FILL);
  gl.polygonOffset(1, 1);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, triangleBuffer);
  const showTextures = control("textures").checked && !falseColour;
  for (const group of triangleGroups) {
    const textured = showTextures && group.surface >= 0;
    gl.uniform1i(uniform("textured"), textured ? 1 : 0);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, textured ? textures[group.surface] : null);
    // Cut-outs cut in every view, textures shown or not.
    const mask = group.surface >= 0 ? shown.lightmaps.maskOf[group.surface] : -1;
    gl.uniform1i(uniform("cut"), mask >= 0 ? 1 : 0);
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, mask >= 0 ? masks[mask] : null);
    gl.activeTexture(gl.TEXTURE0);
    gl.drawElements(gl.TRIANGLES, group.count, gl.UNSIGNED_INT, 4 * group.start);
  }
  gl.uniform1i(uniform("textured"), 0);
  gl.uniform1i(uniform("cut"), 0);
  gl.uniform1i(uniform("lines"), 1);
  if (control("wireframe").checked) {
    gl.uniform4f(uniform("lineColour"), 0, 0, 0, 1);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, lineBuffer);
    gl.drawElements(gl.LINES, lineCount, gl.UNSIGNED_INT, 0);
  }
  if (sensorCount > 0) {
    gl.uniform4f(uniform("lineColour"), 0.1, 0.9, 1, 1);
    gl.disable(gl.DEPTH_TEST);
    gl.bindVertexArray(sensorVao);
    gl.drawArrays(gl.POINTS, 0, sensorCount);
    gl.enable(gl.DEPTH_TEST);
  }
  if (control("links").checked && linkCount > 0) {
    // Faint lines, so that where many links run the picture shows how many.
    const alpha = Math.min(1, Math.max(0.05, 300 / (linkCount / 2)));
    gl.uniform4f(uniform("lineColour"), 1, 0.85, 0.1, alpha);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.depthMask(false);
    gl.bindVertexArray(linkVao);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, linkIndexBuffer);
    gl.drawElements(gl.LINES, linkCount, gl.UNSIGNED_INT, 0);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
  }
}
const redraw = () => requestAnimationFrame(draw);

// Waits for solutions newer than the one shown, loads each; shows the solver's progress
// meanwhile. Each request waits at the server for news (at most two seconds) and brings the
// solution with it (`/api/solution`). Stops when `onSolution` says it is done.
async function watch(onSolution) {
  const text = new TextDecoder();
  for (;;) {
    let parts;
    try {
      const query = `after=${shown.version}&mesh=${shown.meshVersion}`;
      parts = splitParts(await fetchOk(`/api/solution?${query}`).then((r) => r.arrayBuffer()));
    } catch (e) {
      status.textContent = `the server is gone (${e.message})`;
      return;
    }
    const st = JSON.parse(text.decode(parts[0]));
    if (st.error) status.textContent = `error: ${st.error}`;
    if (parts.length > 1) {
      const scene = await load(JSON.parse(text.decode(parts[1])), parts[2] ?? null, parts[3] ?? null);
      if (await onSolution(scene, st)) return;
    } else if (st.solving) {
      const share = st.total > 0 ? ` ${st.done}/${st.total}` : "";
      status.textContent = `solving (${st.phase}${share})…`;
    }
  }
}

// The parts of an `/api/solution` answer (cli/src/view/server.rs, `news`), each in a buffer
// of its own: the status, then the scene, mesh and lightmaps where they came.
function splitParts(buffer) {
  const data = new DataView(buffer);
  const parts = [];
  for (let at = 0; at < buffer.byteLength; ) {
    const length = data.getUint32(at, true);
    parts.push(buffer.slice(at + 4, at + 4 + length));
    at += 4 + 4 * Math.ceil(length / 4);
  }
  return parts;
}

function fillMovable(names) {
  const select = control("move-what");
  select.replaceChildren(...names.map((n) => new Option(n, n)));
}

// With "to" chosen, the fields show where the chosen object or light is now (its centre or
// place, as the latest scene gives it), to be edited into where it goes.
function fillPosition() {
  if (control("move-how").value !== "to" || !shown.scene) return;
  const k = shown.scene.movable.indexOf(control("move-what").value);
  const at = k >= 0 ? shown.scene.positions[k] : null;
  if (!at) {
    timing.textContent = "this has no centre to move to: move it by an offset";
    control("move-how").value = "by";
    return;
  }
  ["move-x", "move-y", "move-z"].forEach((id, i) => { control(id).value = Number(at[i].toFixed(4)); });
}

// Sends a move (`how`: "by" an offset or "to" a position); resolves when the server took it.
let movedAt = null;
async function sendMove(name, how, values) {
  movedAt = performance.now();
  for (const key of ["first", "round", "preview", "solved", "final"]) delete timing.dataset[key];
  timing.textContent = `moving ${name}…`;
  await fetchOk(`/api/move?name=${encodeURIComponent(name)}&${how}=${values.join(",")}`, { method: "POST" });
}

// A pick at canvas pixel (x, y) in CSS pixels, shown in the reading.
async function pickAt(x, y) {
  const dpr = canvas.width / canvas.getBoundingClientRect().width;
  const ray = rayThrough(x * dpr, y * dpr);
  const query = `o=${ray.origin.join(",")}&d=${ray.direction.join(",")}`;
  const pick = await fetchOk(`/api/pick?${query}`).then((r) => r.json());
  reading.textContent = describe(pick, shown.report);
  reading.dataset.lux = pick.hit ? pick.illuminance_lux : "";
  reading.dataset.object = pick.hit ? pick.object : "";
  reading.dataset.point = pick.hit ? pick.point.join(",") : "";
  reading.dataset.version = shown.version;
  shown.picked = pick.hit ? shown.scene.objects.indexOf(pick.object) : -1;
  if (control("links-picked").checked) { uploadLinks(); describeSolution(); redraw(); }
}

// Draws `frames` frames turning round the target; shows the mean and slowest frame time.
function orbit(frames) {
  const times = [];
  let last = performance.now();
  const step = () => {
    view.yaw += (2 * Math.PI) / frames;
    draw();
    gl.finish();
    const now = performance.now();
    times.push(now - last);
    last = now;
    if (times.length < frames) requestAnimationFrame(step);
    else {
      const mean = times.reduce((a, b) => a + b, 0) / times.length;
      const el = control("frames");
      el.textContent = `${frames} frames: mean ${mean.toFixed(1)} ms, slowest ${Math.max(...times).toFixed(1)} ms`;
      el.dataset.meanMs = mean;
    }
  };
  requestAnimationFrame(step);
}

// Renders the current view by path tracing or by final gather over the final solution and
// shows the image over the solution as it refines, until closed (or a move makes it stale).
let rendering = 0;
async function renderView() {
  const image = control("rendered");
  const e = eye();
  const size = [canvas.width, canvas.height];
  const fov = (view.fov * 180) / Math.PI;
  const method = control("render-method").value;
  const query = `o=${e.join(",")}&t=${view.target.join(",")}&fov=${fov}&size=${size.join(",")}`
    + `&method=${method}`;
  const what = method === "final-gather" ? "final gather" : "path tracing";
  const each = method === "final-gather" ? "camera samples" : "paths";
  const { render } = await fetchOk(`/api/render?${query}`, { method: "POST" }).then((r) => r.json());
  rendering = render;
  image.hidden = false;
  control("render-close").hidden = false;
  let passesShown = 0;
  while (rendering === render) {
    const st = await fetchOk("/api/render").then((r) => r.json());
    if (st.render !== render) return;
    if (st.error) { timing.textContent = `render: ${st.error}`; return; }
    if (st.passes > passesShown) {
      passesShown = st.passes;
      image.src = `/api/render.png?pass=${passesShown}`;
      image.dataset.passes = passesShown;
      timing.textContent = `${what}: ${st.samples_per_pixel} ${each} per pixel${st.running ? "…" : ""}`;
    }
    if (!st.running) return;
    await new Promise((done) => setTimeout(done, 300));
  }
}

function closeRender() {
  rendering = 0;
  control("rendered").hidden = true;
  control("render-close").hidden = true;
}

async function main() {
  if (!gl) {
    status.textContent = "this browser has no WebGL2";
    return;
  }
  prog = program();
  vao = gl.createVertexArray();
  linkVao = gl.createVertexArray();
  sensorVao = gl.createVertexArray();
  [triangleBuffer, lineBuffer, linkIndexBuffer] = [gl.createBuffer(), gl.createBuffer(), gl.createBuffer()];
  control("false-colour").checked = params.has("false-color");
  control("wireframe").checked = params.has("wireframe");
  control("links").checked = params.has("links");
  control("links-picked").checked = params.get("links") === "picked";
  control("textures").checked = params.get("textures") !== "off";
  if (TONE_MAPS.includes(params.get("tonemap"))) control("tonemap").value = params.get("tonemap");
  if (params.has("exposure") && Number.isFinite(Number(params.get("exposure")))) control("exposure").value = params.get("exposure");

  for (const id of ["wireframe", "exposure", "false-colour", "textures", "tonemap"]) {
    control(id).addEventListener(id === "exposure" ? "input" : "change", redraw);
  }
  const [rangeMin, rangeMax] = (params.get("range") || "").split(",");
  control("range-min").value = rangeMin ?? "";
  control("range-max").value = rangeMax ?? "";
  control("isolines").value = params.get("isolines") ?? "0";
  for (const id of ["range-min", "range-max", "isolines"]) {
    control(id).addEventListener("input", () => {
      if (!shown.scene) return;
      drawLegend(control("legend"), shown.scene.false_color.stops, falseRange(), isolineCount());
      redraw();
    });
  }
  for (const id of ["links", "links-picked", "links-level"]) {
    control(id).addEventListener("change", async () => {
      if (control("links").checked && !shown.links) await fetchLinks();
      uploadLinks();
      describeSolution();
      redraw();
    });
  }
  window.addEventListener("resize", redraw);
  control("render").addEventListener("click", () => {
    renderView().catch((e) => { timing.textContent = `render: ${e.message}`; });
  });
  control("render-close").addEventListener("click", closeRender);
  control("move").addEventListener("click", () => {
    closeRender();
    const values = ["move-x", "move-y", "move-z"].map((id) => Number(control(id).value) || 0);
    sendMove(control("move-what").value, control("move-how").value, values)
      .catch((e) => { timing.textContent = `error: ${e.message}`; });
  });
  control("move-what").addEventListener("change", fillPosition);
  control("move-how").addEventListener("change", () => {
    if (control("move-how").value === "by") {
      for (const id of ["move-x", "move-y", "move-z"]) control(id).value = 0;
    }
    fillPosition();
  });

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
    if (!clicked || !shown.scene) return;
    const rect = canvas.getBoundingClientRect();
    await pickAt(e.clientX - rect.left, e.clientY - rect.top);
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    view.distance *= Math.exp(e.deltaY * 0.001);
    redraw();
  }, { passive: false });
  window.addEventListener("keydown", (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
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

  // The address's actions, once the first final solution is drawn: the move (if any), then
  // — on the final solution of the moved scene — the pick and the orbit.
  const asked = params.get("move");
  let movesWanted = null;
  const [pickX, pickY] = (params.get("pick") || "").split(",").map(Number);
  await watch(async (scene, st) => {
    if (movedAt !== null && scene.moves === st.moves) {
      const ms = (performance.now() - movedAt).toFixed(0);
      timing.dataset.first ??= ms;
      timing.dataset[scene.stage] ??= ms;
      const at = (key) => timing.dataset[key] ?? "–";
      const links = st.links_kept + st.links_computed;
      const kept = links > 0 ? `; ${st.links_kept} of ${links} patch links kept from the solve before` : "";
      // The final solve is shown before its report is gathered when it has that step.
      const solved = timing.dataset.solved ? `, final solve in ${at("solved")} ms` : "";
      const server = [st.preview_seconds, st.solved_seconds, st.final_seconds]
        .filter((t, k) => k !== 1 || t != null).map((t) => t?.toFixed(3) ?? "–").join(" / ");
      timing.textContent = `after the move: first drawn in ${at("first")} ms, preview in ${at("preview")} ms${solved}, final in ${at("final")} ms (server ${server} s${kept})`;
    }
    if (scene.stage !== "final" || st.moves !== scene.moves) return false;
    if (asked && movesWanted === null) {
      const [name, by] = asked.split(":");
      movesWanted = scene.moves + 1;
      await sendMove(name, "by", (by || "").split(",").map(Number));
      return false;
    }
    if (movesWanted !== null && scene.moves < movesWanted) return false;
    if (Number.isFinite(pickX) && Number.isFinite(pickY) && reading.dataset.version === undefined) {
      await pickAt(pickX * canvas.clientWidth, pickY * canvas.clientHeight);
    }
    if (params.has("orbit") && control("frames").dataset.meanMs === undefined) {
      orbit(Number(params.get("orbit")) || 100);
    }
    return params.has("still");
  });
}

// The legend of the false-colour scale: the unit, a bar from the scale's stops (high end up)
// and the values at its levels (the isolines', or five).
function drawLegend(legend, stops, range, isolines) {
  const css = (c) => `rgb(${c[0]}, ${c[1]}, ${c[2]})`;
  const bar = document.createElement("div");
  bar.className = "bar";
  bar.style.background = `linear-gradient(to top, ${stops.map((s) => `${css(s[1])} ${100 * s[0]}%`).join(", ")})`;
  const labels = document.createElement("div");
  labels.className = "labels";
  const [low, high] = range;
  const steps = isolines > 0 ? isolines : 4;
  for (let k = steps; k >= 0; k--) {
    const label = document.createElement("div");
    label.textContent = String(+(low + ((high - low) * k) / steps).toPrecision(4));
    labels.appendChild(label);
  }
  const unit = document.createElement("div");
  unit.textContent = "lux";
  legend.replaceChildren(unit, bar, labels);
}

// The sensors' readings from the report, one line each.
function listSensors(report) {
  const list = control("sensors");
  const sensors = (report && report.sensors) || [];
  list.textContent = sensors
    .map((r) => `${r.name}: ${r.illuminance_lux.toPrecision(4)} lux (direct ${r.direct_illuminance_lux.toPrecision(4)}, indirect ${r.indirect_illuminance_lux.toPrecision(4)})`)
    .join("\n");
  list.dataset.count = sensors.length;
}

// One pick in words, with the report's row for the object hit.
function describe(pick, report) {
  if (!pick.hit) return "nothing there";
  const row = report && report.objects.find((o) => o.name === pick.object);
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
