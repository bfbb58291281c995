// WebGL2 drawing: the surface lit and shaded (two-sided, Blinn–Phong), the floaters as small
// discs on it (Turk & O'Brien 2002, §5), the handles as round points coloured by kind, and normal
// handles as sticks from their boundary point.

const SURFACE_VS = `#version 300 es
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view, projection;
out vec3 n, v;
void main() {
  vec4 p = view * vec4(position, 1.0);
  n = mat3(view) * normal;
  v = -p.xyz;
  gl_Position = projection * p;
}`;

const SURFACE_FS = `#version 300 es
precision highp float;
in vec3 n, v;
uniform vec3 tint;
out vec4 colour;
void main() {
  vec3 N = normalize(n), V = normalize(v);
  vec3 base = tint;
  if (!gl_FrontFacing) { N = -N; base = vec3(0.45, 0.5, 0.7); }
  // A key light above left, a dimmer fill from the right, and sky-like ambient.
  vec3 L = normalize(vec3(-0.4, 0.8, 0.6));
  vec3 F = normalize(vec3(0.8, -0.1, 0.5));
  float diffuse = max(dot(N, L), 0.0);
  float fill = max(dot(N, F), 0.0);
  float specular = pow(max(dot(N, normalize(L + V)), 0.0), 48.0);
  colour = vec4(base * (0.28 + 0.62 * diffuse + 0.3 * fill) + 0.3 * specular, 1.0);
}`;

const MARK_VS = `#version 300 es
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 colour;
uniform mat4 view, projection;
uniform float size;
out vec3 c;
void main() {
  gl_Position = projection * view * vec4(position, 1.0);
  gl_PointSize = size;
  c = colour;
}`;

const MARK_FS = `#version 300 es
precision mediump float;
in vec3 c;
uniform bool round;
out vec4 colour;
void main() {
  if (round && length(gl_PointCoord - 0.5) > 0.5) discard;
  colour = vec4(c, 1.0);
}`;

/// Colours of the handle kinds: boundary, interior, exterior, normal tip; selected.
export const KIND_COLOURS = [[0.15, 0.35, 0.85], [0.1, 0.6, 0.2], [0.85, 0.15, 0.15], [0.95, 0.75, 0.1]];
const SELECTED = [1, 1, 1];

/// Fills vertex array `vao` with three-float attributes: [location, buffer, data] each.
function attributes(gl, vao, list) {
  gl.bindVertexArray(vao);
  for (const [location, buffer, data] of list) {
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
    gl.enableVertexAttribArray(location);
    gl.vertexAttribPointer(location, 3, gl.FLOAT, false, 0, 0);
  }
}

function program(gl, vs, fs) {
  const p = gl.createProgram();
  for (const [type, source] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    gl.attachShader(p, s);
  }
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  return p;
}

/// Whether WebGL runs on the processor, not a graphics card (SwiftShader, Mesa's llvmpipe or
/// softpipe, Windows' WARP): asked of a throwaway context, since a canvas keeps the attributes
/// of its first one.
export function softwareWebGL() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return false;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software|basic render|warp/i.test(name);
}

export class Renderer {
  constructor(canvas) {
    // Multisampling costs a software renderer about 11 ms a frame at 1000 × 700 (a quarter
    // of a studio edit), taken from the cores that solve and re-mesh: there the edges are
    // left unsmoothed. A graphics card smooths them for nothing.
    this.software = softwareWebGL();
    const gl = canvas.getContext('webgl2', { antialias: !this.software, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    this.gl = gl;
    this.surface = program(gl, SURFACE_VS, SURFACE_FS);
    this.marks = program(gl, MARK_VS, MARK_FS);
    this.surfaceVao = gl.createVertexArray();
    this.buffers = { position: gl.createBuffer(), normal: gl.createBuffer(), index: gl.createBuffer() };
    this.discVao = gl.createVertexArray();
    this.discBuffers = { position: gl.createBuffer(), normal: gl.createBuffer() };
    this.discVertices = 0;
    this.markVao = gl.createVertexArray();
    this.markBuffers = { position: gl.createBuffer(), colour: gl.createBuffer() };
    this.count = 0;
    this.points = 0;
    this.lines = 0;
  }

  /// New surface buffers: positions and normals (3 floats a vertex), indices (3 a triangle).
  setSurface(positions, normals, indices) {
    const gl = this.gl;
    attributes(gl, this.surfaceVao, [[0, this.buffers.position, positions], [1, this.buffers.normal, normals]]);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.buffers.index);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.DYNAMIC_DRAW);
    gl.bindVertexArray(null);
    this.count = indices.length;
  }

  /// New floaters: seven numbers each (centre, outward normal, radius), drawn as discs of
  /// eight triangles lifted a little off the surface.
  setDiscs(floaters) {
    const positions = [], normals = [];
    const SIDES = 8;
    for (let k = 0; k < floaters.length; k += 7) {
      const n = [floaters[k + 3], floaters[k + 4], floaters[k + 5]], r = floaters[k + 6];
      const c = [0, 1, 2].map((i) => floaters[k + i] + 0.08 * r * n[i]);
      // Two unit vectors across the normal.
      const a = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
      const u = [n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]];
      const lu = Math.hypot(...u);
      const e1 = u.map((x) => x / lu);
      const e2 = [n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]];
      const rim = (j) => {
        const t = 2 * Math.PI * j / SIDES;
        return c.map((v, i) => v + r * (Math.cos(t) * e1[i] + Math.sin(t) * e2[i]));
      };
      for (let j = 0; j < SIDES; j++) {
        positions.push(...c, ...rim(j), ...rim(j + 1));
        normals.push(...n, ...n, ...n);
      }
    }
    const gl = this.gl;
    attributes(gl, this.discVao, [[0, this.discBuffers.position, new Float32Array(positions)], [1, this.discBuffers.normal, new Float32Array(normals)]]);
    gl.bindVertexArray(null);
    this.discVertices = positions.length / 3;
  }

  /// New handles: [{ index, kind, position, base }], the selected item's index.
  setHandles(handles, selected) {
    const points = [], colours = [];
    for (const h of handles) {
      points.push(...h.position);
      colours.push(...(h.index === selected ? SELECTED : KIND_COLOURS[h.kind]));
    }
    const sticks = handles.filter((h) => h.kind === 3);
    for (const h of sticks) {
      points.push(...h.base, ...h.position);
      colours.push(...KIND_COLOURS[3], ...KIND_COLOURS[3]);
    }
    const gl = this.gl;
    attributes(gl, this.markVao, [[0, this.markBuffers.position, new Float32Array(points)], [1, this.markBuffers.colour, new Float32Array(colours)]]);
    gl.bindVertexArray(null);
    this.points = handles.length;
    this.lines = sticks.length * 2;
  }

  draw(camera, showHandles) {
    const gl = this.gl;
    const canvas = gl.canvas;
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.87, 0.9, 0.95, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    const view = camera.view(), projection = camera.projection();
    if (this.count > 0) {
      gl.useProgram(this.surface);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.surface, 'view'), false, view);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.surface, 'projection'), false, projection);
      gl.uniform3f(gl.getUniformLocation(this.surface, 'tint'), 0.80, 0.42, 0.22);
      gl.bindVertexArray(this.surfaceVao);
      gl.drawElements(gl.TRIANGLES, this.count, gl.UNSIGNED_INT, 0);
      if (this.discVertices > 0) {
        gl.uniform3f(gl.getUniformLocation(this.surface, 'tint'), 0.95, 0.9, 0.55);
        gl.bindVertexArray(this.discVao);
        gl.drawArrays(gl.TRIANGLES, 0, this.discVertices);
      }
    }
    if (showHandles && this.points > 0) {
      gl.useProgram(this.marks);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.marks, 'view'), false, view);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.marks, 'projection'), false, projection);
      gl.uniform1f(gl.getUniformLocation(this.marks, 'size'), 11 * (window.devicePixelRatio || 1));
      gl.bindVertexArray(this.markVao);
      // Handles show through the surface, so that those behind it can still be grabbed.
      gl.disable(gl.DEPTH_TEST);
      gl.uniform1i(gl.getUniformLocation(this.marks, 'round'), 0);
      gl.drawArrays(gl.LINES, this.points, this.lines);
      gl.uniform1i(gl.getUniformLocation(this.marks, 'round'), 1);
      gl.drawArrays(gl.POINTS, 0, this.points);
    }
    gl.bindVertexArray(null);
  }
}
