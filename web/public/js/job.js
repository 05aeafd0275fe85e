// A job's page: its planning stages with progress, the plan's figures, a layer viewer (the plan's
// own layer previews: fibre over the sigma map, PLA paths) with the robot's last confirmed
// position on the layer being printed, a 3D view of the toolpaths with a layer range, another
// job's plan side by side (a baseline of the same part), and the result at the end.
import { el, kv, fixed, formatDuration, errorText } from "./ui.js";
import { stateBadge, act, actions } from "./jobs.js";
import { ToolpathView } from "./toolpath_view.js";

// The planner's stages in order (the progress events' `stage`).
const stages = ["queued", "read", "fea", "principal", "incompatible_removal", "mst_reorientation", "slice",
                "layers", "mechanics", "write", "robot"];

let state = null;  // {id, job, report, layer, unsub[], view3d}

function planFigures(report) {
  if (!report) return el("p", { class: "muted" }, "no plan yet");
  const q = report.quality || {}, f = report.fibre || {}, r = report.robot || {}, m = report.mechanics;
  const layers = report.layers || {};
  return kv([
    ["strategy", report.strategy],
    ["layers", `${(layers.pla || 0) + (layers.ccf || 0)} (${layers.pla || 0} PLA, ${layers.ccf || 0} CCF)`],
    ["fibre", `${fixed(f.length_m, 2, " m")} in ${f.paths ?? "?"} paths (mean ${fixed(f.mean_path_mm, 0, " mm")})`],
    ["fibre coverage", f.coverage ? `${fixed(f.coverage.coverage, 3)} (${fixed(100 * f.coverage.covered, 1, "%")} of the fibre region under a ribbon)` : "–"],
    ["PLA", fixed((report.pla || {}).length_m, 1, " m")],
    ["alignment (weighted |cos|)", fixed(q.alignment_weighted_cos, 3)],
    ["density–stress correlation", fixed(q.density_sigma_p_correlation, 2)],
    ["min fibre spacing", fixed(f.min_spacing_mm, 2, " mm")],
    ["print time (robot)", formatDuration(r.duration_s)],
    ["stiffness", m ? `${fixed(m.reinforced?.stiffness_n_per_mm, 0, " N/mm")} (×${fixed(m.stiffness_gain, 2)} over no fibre)` : "–"],
    ["planned in", fixed((report.timings_s || {}).total, 1, " s")],
  ]);
}

function progressBox(job) {
  if (job.state === "planning") {
    const p = job.planning || { stage: "queued", fraction: 0 };
    return el("div", { id: "planning-progress" },
      el("ol", { class: "stages" }, stages.map((s) => el("li", { class: s === p.stage ? "state" : "muted" }, s))),
      el("progress", { max: 1, value: p.fraction }), ` ${p.stage} ${Math.round(100 * p.fraction)}%`);
  }
  if (job.print) {
    const p = job.print;
    return el("div", { id: "print-progress" },
      el("div", { class: "big" }, `layer ${p.layer}/${p.layers}`, p.eta_s !== undefined ? ` · ETA ${formatDuration(p.eta_s)}` : ""),
      el("progress", { max: 1, value: p.fraction }),
      ` event ${p.event}/${p.events}, ${formatDuration(p.elapsed_s)} elapsed`);
  }
  return null;
}

function resultBox(job) {
  const r = job.result;
  if (!r) return null;
  return el("section", { class: "card", id: "job-result" }, el("h2", {}, "Result"), kv([
    ["outcome", stateBadge(job)],
    ["events", `${r.events_done}/${r.events}`],
    ["elapsed", `${formatDuration(r.elapsed_s)} (robot time ${formatDuration(r.robot_time_s)})`],
    // Robot event to extruder command, per event kind.
    ["sync latency p99", r.latency_ms ? Object.entries(r.latency_ms).map(([kind, l]) => `${kind} ${fixed(l.p99, 2)}`).join(", ") + " ms" : "–"],
    ["cut position error", r.cut_error_mm ? `${fixed(r.cut_error_mm.median, 2)} mm median, ${fixed(r.cut_error_mm.max, 2)} mm max` : "–"],
    ["shortfalls", (r.shortfalls || []).length ? JSON.stringify(r.shortfalls) : "none"],
    ["reason", r.reason || ""],
  ]));
}

async function fetchText(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${url}: ${res.status}`);
  return res.text();
}

const layerFile = (i) => `layer_${String(i).padStart(4, "0")}.svg`;

// One plan's layer preview as an inline SVG, with a marker where the robot was last.
async function layerSvg(jobId, index) {
  const text = await fetchText(`api/jobs/${jobId}/preview/${layerFile(index)}`);
  const doc = new DOMParser().parseFromString(text, "image/svg+xml");
  const svg = document.importNode(doc.documentElement, true);
  svg.querySelectorAll("script").forEach((s) => s.remove());
  return svg;
}

function placeRobot(svg, position) {
  svg.querySelector(".robot")?.remove();
  const x0 = parseFloat(svg.dataset.modelX0), y0 = parseFloat(svg.dataset.modelY0);
  if (!position || !isFinite(x0)) return;
  const marker = document.createElementNS("http://www.w3.org/2000/svg", "circle");
  marker.setAttribute("class", "robot");
  marker.setAttribute("cx", position[0] - x0);
  marker.setAttribute("cy", y0 - position[1]);
  marker.setAttribute("r", 1.6);
  marker.setAttribute("fill", "none");
  marker.setAttribute("stroke", "#00a0ff");
  marker.setAttribute("stroke-width", 0.6);
  svg.append(marker);
}

async function showLayer(index) {
  const s = state;
  if (!s.report) return;
  const count = (s.report.layers.pla || 0) + (s.report.layers.ccf || 0);
  s.layer = Math.min(Math.max(0, index), count - 1);
  s.layerLabel.textContent = `layer ${s.layer + 1} of ${count}`;
  s.slider.value = s.layer;
  try {
    const svg = await layerSvg(s.id, s.layer);
    if (s !== state) return;
    s.svg = svg;
    const printing = s.job.print && s.job.print.layer - 1 === s.layer;
    placeRobot(svg, printing ? s.job.print.position_mm : null);
    s.layerBox.replaceChildren(svg);
    if (s.compareId) s.compareBox.replaceChildren(await layerSvg(s.compareId, s.layer));
  } catch (e) {
    s.layerBox.replaceChildren(el("p", { class: "error" }, errorText(e)));
  }
}

async function loadPlan() {
  const s = state;
  try {
    s.report = JSON.parse(await fetchText(`api/jobs/${s.id}/report.json`));
  } catch {
    s.report = null;
    return;
  }
  s.figures.replaceChildren(planFigures(s.report));
  const count = (s.report.layers.pla || 0) + (s.report.layers.ccf || 0);
  s.slider.max = count - 1;
  s.rangeTo.value = count;
  s.viewer.hidden = false;
  await showLayer(s.job.print ? s.job.print.layer - 1 : 0);
  s.view3d.load(`api/jobs/${s.id}/toolpaths.json`).catch((e) => s.view3dBox.append(el("p", { class: "error" }, errorText(e))));
}

function redraw() {
  const s = state;
  s.head.replaceChildren(el("h1", {}, `Job ${s.job.id}: ${s.job.name} `, stateBadge(s.job)),
    el("p", { class: "error", id: "job-reason" }, s.job.reason || ""));
  s.progress.replaceChildren(progressBox(s.job) || "");
  s.result.replaceChildren(resultBox(s.job) || "");
  s.actions.replaceChildren(...(actions[s.job.state] || []).map((a) =>
    el("button", { dataset: { action: a }, class: a === "start" ? "primary" : a === "abort" ? "danger" : "",
                   onclick: () => act(s.rpc, a, s.job.id, s.message) }, a)));
}

export async function render(main, { rpc }, arg) {
  const id = Number(arg);
  state = { id, rpc, unsub: [], layer: 0, head: el("div"), progress: el("div"), result: el("div"),
            actions: el("div", { class: "actions" }), message: el("p", { class: "error", role: "alert", id: "job-message" }),
            figures: el("div", { id: "plan-figures" }), layerBox: el("div", { class: "layer-view", id: "layer-view" }),
            compareBox: el("div", { class: "layer-view", id: "compare-view" }), layerLabel: el("span"),
            slider: el("input", { type: "range", min: 0, max: 0, value: 0, id: "layer-slider" }),
            view3dBox: el("div", { id: "three-view" }), viewer: el("section", { class: "card", hidden: true }) };
  const s = state;
  s.slider.addEventListener("input", () => showLayer(Number(s.slider.value)));
  const compare = el("select", { id: "compare-job" }, el("option", { value: "" }, "compare with another job…"));
  compare.addEventListener("change", () => {
    s.compareId = compare.value ? Number(compare.value) : null;
    s.compareBox.replaceChildren();
    s.compareBox.hidden = !s.compareId;
    showLayer(s.layer);
  });
  s.compareBox.hidden = true;  // until another job is chosen
  const range = [el("input", { type: "number", min: 1, value: 1, id: "range-from", size: 4 }),
                 el("input", { type: "number", min: 1, value: 1, id: "range-to", size: 4 })];
  s.rangeTo = range[1];
  range.forEach((r) => r.addEventListener("change", () => s.view3d.setRange(Number(range[0].value) - 1, Number(range[1].value) - 1)));
  s.viewer.append(el("h2", {}, "Layers"),
    el("div", {}, el("button", { onclick: () => showLayer(s.layer - 1) }, "◀"), " ", s.slider, " ",
       el("button", { onclick: () => showLayer(s.layer + 1) }, "▶"), " ", s.layerLabel, " ", compare),
    el("div", { class: "side-by-side" }, s.layerBox, s.compareBox),
    el("h2", {}, "3D"), el("div", {}, "layers ", range[0], " to ", range[1]), s.view3dBox);
  main.append(s.head, s.actions, s.message, s.progress,
              el("div", { class: "cards" }, el("section", { class: "card" }, el("h2", {}, "Plan"), s.figures)), el("p"),
              s.result, s.viewer);
  s.view3d = new ToolpathView(s.view3dBox);

  // Subscribed before the job is read: a change between the two (a small job plans in a tenth of
  // a second) is then in what job.get answers, or in an event after it, never in neither.
  try {
    await rpc.subscribe([String(id)]);
    s.job = await rpc.call("job.get", { job: id });
  } catch (e) {
    main.replaceChildren(el("p", { class: "error" }, errorText(e)));
    return;
  }
  redraw();
  s.unsub.push(rpc.on("notify.job_state", async (job) => {
    if (job.id !== id || s !== state) return;
    const wasPlanning = s.job.state === "planning" || s.job.state === "failed";
    s.job = job;
    redraw();
    if (!job.print && s.svg) placeRobot(s.svg, null);  // the print ended: no robot on the layer
    if (wasPlanning && job.state !== "planning" && job.plan) await loadPlan();
  }));
  s.unsub.push(rpc.on("notify.job_progress", (p) => {
    if (p.job !== id || s !== state) return;
    if (p.planning) s.job.planning = p.planning;
    if (p.print) {
      const layerChanged = !s.job.print || s.job.print.layer !== p.print.layer;
      s.job.print = p.print;
      if (layerChanged && s.report) showLayer(p.print.layer - 1);
      else if (s.svg && p.print.layer - 1 === s.layer) placeRobot(s.svg, p.print.position_mm);
    }
    s.progress.replaceChildren(progressBox(s.job) || "");
    s.head.querySelector("h1 .state")?.replaceWith(stateBadge(s.job));  // its layer i/N
  }));
  for (const other of await rpc.call("job.list"))
    if (other.id !== id && other.plan) compare.append(el("option", { value: other.id }, `job ${other.id}: ${other.name}`));
  if (s.job.plan) await loadPlan();
}

export function leave() {
  if (!state) return;
  for (const u of state.unsub) u();
  state.view3d?.dispose();
  state = null;
}
