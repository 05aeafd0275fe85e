// The History page (docs/history.md): the jobs the cell ended, newest first, with the filament
// the board fed beside the plan's; a chart of prints and fibre used per day; the CSV download
// (the service writes it: RFC 4180, formula text prefixed). New records arrive as notify.history.
import { el, fixed, errorText } from "./ui.js";

let unsubscribe = null;
let plot = null;

function used(r, kind) {
  return `${fixed(r[`${kind}_used_m`], 2)} / ${fixed(r[`${kind}_planned_m`], 2)}`;
}

function row(r) {
  return el("tr", { dataset: { record: r.id } },
    el("td", {}, el("a", { href: `#/job/${r.id}` }, String(r.id))),
    el("td", {}, r.name),
    el("td", { class: `state ${r.outcome}` }, r.outcome),
    el("td", {}, (r.ended_at || "").replace("T", " ").replace("Z", "")),
    el("td", {}, `${r.layers_printed}/${r.layers_total}`),
    el("td", {}, used(r, "fibre")),
    el("td", {}, used(r, "pla")),
    el("td", {}, fixed(r.cut_error_p99_mm, 2)),
    el("td", {}, r.started_by || r.submitted_by || ""),
    el("td", { class: "reason" }, r.reason || ""));
}

// Prints and fibre used per day (UTC), for the chart.
function perDay(records) {
  const days = new Map();
  for (const r of records) {
    const day = (r.ended_at || "").slice(0, 10);
    if (!day) continue;
    const d = days.get(day) || { prints: 0, fibre: 0 };
    d.prints += r.outcome === "completed" || r.outcome === "completed_with_warnings" ? 1 : 0;
    d.fibre += r.fibre_used_m || 0;
    days.set(day, d);
  }
  const sorted = [...days.keys()].sort();
  return [sorted.map((d) => Date.parse(`${d}T00:00:00Z`) / 1000),
          sorted.map((d) => days.get(d).prints), sorted.map((d) => days.get(d).fibre)];
}

function makePlot(box, records) {
  if (plot) plot.destroy();
  plot = null;
  if (typeof window.uPlot === "undefined" || !records.length) return;
  const bars = window.uPlot.paths && window.uPlot.paths.bars ? window.uPlot.paths.bars({ size: [0.6, 40] }) : undefined;
  plot = new window.uPlot({
    width: Math.max(300, box.clientWidth - 20), height: 220,
    // A day either side: one day alone would spread over years.
    scales: { x: { time: true, range: (u, min, max) => [min - 86400, max + 86400] }, m: {} },
    series: [{}, { label: "prints completed", stroke: "#1f5fbf", fill: "#1f5fbf55", paths: bars },
             { label: "fibre used [m]", stroke: "#d62728", width: 2, scale: "m" }],
    axes: [{}, { label: "prints" }, { side: 1, scale: "m", label: "fibre [m]", grid: { show: false } }],
  }, perDay(records), box);
}

async function downloadCsv(rpc, message) {
  try {
    const { csv } = await rpc.call("history.list", { format: "csv" });
    const link = el("a", { href: URL.createObjectURL(new Blob([csv], { type: "text/csv" })),
                           download: "fibrecell-history.csv" });
    document.body.append(link);
    link.click();
    link.remove();
    message.textContent = "";
  } catch (e) {
    message.textContent = errorText(e);
  }
}

export async function render(main, { rpc }) {
  const message = el("p", { class: "error", role: "alert", id: "history-message" });
  const chart = el("div", { id: "history-chart" });
  const body = el("tbody", { id: "history-rows" });
  const download = el("button", { id: "history-csv", onclick: () => downloadCsv(rpc, message) }, "Download CSV");
  main.append(
    el("section", { class: "card" }, el("h2", {}, "Prints and fibre per day"), chart),
    el("section", { class: "card" }, el("h2", {}, "History ", download), message,
       el("table", { class: "jobs", id: "history-table" },
          el("thead", {}, el("tr", {}, ["job", "name", "outcome", "ended (UTC)", "layers",
             "fibre m used / plan", "PLA m used / plan", "cut p99 mm", "started by", "reason"]
             .map((h) => el("th", {}, h)))),
          body)));
  let records = [];
  const redraw = () => {
    body.replaceChildren(...records.slice().reverse().map(row));
    makePlot(chart, records);
  };
  unsubscribe = rpc.on("notify.history", (r) => {
    records = records.filter((x) => x.id !== r.id).concat([r]);
    redraw();
  });
  try {
    await rpc.subscribe(["history"]);
    records = (await rpc.call("history.list")).records;
    redraw();
  } catch (e) {
    message.textContent = errorText(e);
  }
}

export function leave() {
  if (unsubscribe) unsubscribe();
  if (plot) plot.destroy();
  plot = null;
}
