// An orbit camera: a target, a distance and two angles; its matrices for WebGL and the ray
// through a pixel for picking. Matrices are column-major Float32Arrays.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => { const n = Math.hypot(...a) || 1; return a.map((v) => v / n); };

export class Camera {
  constructor() {
    this.target = [0, 0, 0];
    this.distance = 5;
    this.yaw = 0.6;
    this.pitch = 0.35;
    this.fov = 40 * Math.PI / 180;
    this.width = 1;
    this.height = 1;
  }

  /// Frames a box: the target at its centre, the distance to see all of it.
  frame(lo, hi) {
    this.target = lo.map((v, i) => (v + hi[i]) / 2);
    const radius = Math.hypot(...sub(hi, lo)) / 2 || 1;
    // The narrower of the vertical and horizontal fields of view must hold the box.
    const horizontal = 2 * Math.atan(Math.tan(this.fov / 2) * this.width / this.height);
    this.distance = radius / Math.sin(Math.min(this.fov, horizontal) / 2) * 1.05;
  }

  eye() {
    const c = Math.cos(this.pitch);
    return [
      this.target[0] + this.distance * c * Math.sin(this.yaw),
      this.target[1] + this.distance * Math.sin(this.pitch),
      this.target[2] + this.distance * c * Math.cos(this.yaw),
    ];
  }

  /// The camera's right, up and forward unit vectors.
  basis() {
    const forward = normalize(sub(this.target, this.eye()));
    const right = normalize(cross(forward, [0, 1, 0]));
    const up = cross(right, forward);
    return { right, up, forward };
  }

  orbit(dx, dy) {
    this.yaw -= dx * 0.008;
    this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + dy * 0.008));
  }

  pan(dx, dy) {
    const { right, up } = this.basis();
    const s = this.distance * 0.0015;
    this.target = this.target.map((v, i) => v - right[i] * dx * s + up[i] * dy * s);
  }

  zoom(steps) {
    this.distance *= Math.exp(steps * 0.1);
  }

  view() {
    const e = this.eye();
    const { right: r, up: u, forward: f } = this.basis();
    return new Float32Array([
      r[0], u[0], -f[0], 0,
      r[1], u[1], -f[1], 0,
      r[2], u[2], -f[2], 0,
      -dot(r, e), -dot(u, e), dot(f, e), 1,
    ]);
  }

  projection() {
    const t = 1 / Math.tan(this.fov / 2);
    const aspect = this.width / this.height;
    const near = this.distance * 0.01;
    const far = this.distance * 20;
    return new Float32Array([
      t / aspect, 0, 0, 0,
      0, t, 0, 0,
      0, 0, (far + near) / (near - far), -1,
      0, 0, (2 * far * near) / (near - far), 0,
    ]);
  }

  /// The ray through canvas pixel (x, y): { origin, direction } in model coordinates.
  ray(x, y) {
    const { right, up, forward } = this.basis();
    const t = Math.tan(this.fov / 2);
    const aspect = this.width / this.height;
    const px = (2 * x / this.width - 1) * t * aspect;
    const py = (1 - 2 * y / this.height) * t;
    const direction = normalize(forward.map((f, i) => f + right[i] * px + up[i] * py));
    return { origin: this.eye(), direction };
  }

  /// The canvas pixel of a point, and its depth along the view.
  project(p) {
    const { right, up, forward } = this.basis();
    const d = sub(p, this.eye());
    const z = dot(d, forward);
    const t = Math.tan(this.fov / 2);
    const aspect = this.width / this.height;
    const x = (dot(d, right) / z / (t * aspect) + 1) / 2 * this.width;
    const y = (1 - dot(d, up) / z / t) / 2 * this.height;
    return { x, y, z };
  }

  /// Where the ray through pixel (x, y) meets the plane through `p` facing the camera.
  onPlaneFacing(p, x, y) {
    const { forward } = this.basis();
    const { origin, direction } = this.ray(x, y);
    const s = dot(sub(p, origin), forward) / dot(direction, forward);
    return origin.map((o, i) => o + s * direction[i]);
  }
}
