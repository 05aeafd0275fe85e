// The 3D view of a plan's toolpaths (toolpaths.json): PLA paths blue, fibre red, each layer at its
// z, a layer range to look inside, drag to turn, wheel to zoom. three.js from npm (web/vendor).
import * as THREE from "../vendor/three.module.js";

const colours = { perimeter: 0x1f5fbf, infill: 0xf28e2b, fibre: 0xd62728, "fibre-boundary": 0x111111 };

export class ToolpathView {
  constructor(container) {
    this.container = container;
    this.layers = [];  // THREE.Group per layer
    this.renderer = null;
    try {
      this.renderer = new THREE.WebGLRenderer({ antialias: true });
    } catch (e) {
      container.textContent = `no 3D view: ${e.message}`;
      return;
    }
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xeef1f4);
    this.camera = new THREE.PerspectiveCamera(40, 1, 1, 5000);
    container.append(this.renderer.domElement);
    this.turn = { azimuth: -0.6, elevation: 0.7, distance: 400, target: new THREE.Vector3() };
    this.bindControls();
    this.resize = new ResizeObserver(() => this.draw());
    this.resize.observe(container);
  }

  async load(url) {
    if (!this.renderer) return;
    const res = await fetch(url);
    if (!res.ok) throw new Error(`toolpaths: ${res.status}`);
    const plan = await res.json();
    const box = new THREE.Box3();
    for (const layer of plan.layers) {
      const group = new THREE.Group();
      const byRole = new Map();
      for (const path of layer.paths) {
        const pts = path.closed ? [...path.points, path.points[0]] : path.points;
        const list = byRole.get(path.role) || [];
        for (let i = 1; i < pts.length; ++i)
          list.push(pts[i - 1][0], pts[i - 1][1], layer.z, pts[i][0], pts[i][1], layer.z);
        byRole.set(path.role, list);
      }
      for (const [role, list] of byRole) {
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute("position", new THREE.Float32BufferAttribute(list, 3));
        geometry.computeBoundingBox();
        box.union(geometry.boundingBox);
        group.add(new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: colours[role] ?? 0x444444 })));
      }
      this.layers.push(group);
      this.scene.add(group);
    }
    box.getCenter(this.turn.target);
    this.turn.distance = 1.6 * box.getSize(new THREE.Vector3()).length();
    this.draw();
  }

  // Layers from..to (0-based, inclusive) shown.
  setRange(from, to) {
    this.layers.forEach((g, i) => { g.visible = i >= from && i <= to; });
    this.draw();
  }

  bindControls() {
    const canvas = this.renderer.domElement;
    let last = null;
    canvas.addEventListener("pointerdown", (e) => { last = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener("pointerup", () => { last = null; });
    canvas.addEventListener("pointermove", (e) => {
      if (!last) return;
      this.turn.azimuth -= (e.clientX - last[0]) * 0.01;
      this.turn.elevation = Math.min(1.5, Math.max(-1.5, this.turn.elevation + (e.clientY - last[1]) * 0.01));
      last = [e.clientX, e.clientY];
      this.draw();
    });
    canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      this.turn.distance *= Math.exp(e.deltaY * 0.001);
      this.draw();
    }, { passive: false });
  }

  draw() {
    if (!this.renderer) return;
    const w = this.container.clientWidth || 600, h = this.container.clientHeight || 420;
    this.renderer.setSize(w, h, false);
    this.renderer.domElement.style.width = "100%";
    this.camera.aspect = w / h;
    const t = this.turn;
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(
      t.target.x + t.distance * Math.cos(t.elevation) * Math.cos(t.azimuth),
      t.target.y + t.distance * Math.cos(t.elevation) * Math.sin(t.azimuth),
      t.target.z + t.distance * Math.sin(t.elevation));
    this.camera.lookAt(t.target);
    this.camera.updateProjectionMatrix();
    this.renderer.render(this.scene, this.camera);
  }

  dispose() {
    if (!this.renderer) return;
    this.resize.disconnect();
    for (const g of this.layers) g.traverse((o) => { o.geometry?.dispose(); o.material?.dispose(); });
    this.renderer.dispose();
  }
}
