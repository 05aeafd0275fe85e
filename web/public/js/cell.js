// The Cell page: the board's and the robot's link states, both hotends over the last 30 minutes,
// the robot's state and event, the sync's latency and cut position error, and the E-stop.
import { el, kv, fixed, errorText } from "./ui.js";

let plot = null;
let unsubscribe = null;
let resizeObserver = null;

function latency(sync, key) {
  const s = sync && sync[key];
  return s ? `${fixed(s.median, 1)} median, ${fixed(s.p99, 1)} p99, ${fixed(s.max, 1)} max` : "–";
}

function details(status) {
  const b = status.board || {}, r = status.robot || {}, sync = status.sync || {};
  return el("div", { class: "cards" },
    el("section", { class: "card", id: "board-card" }, el("h2", {}, "Extruder board"), kv([
      ["link", el("span", { class: "state", id: "board-state" }, b.state || "–")],
      ["fault", b.fault || "none"],
      ["emergency parser", b.emergency_parser === undefined ? "–"
        : b.emergency_parser ? "yes" : el("span", { class: "error" }, "no: an abort cannot break a heat-up")],
      ["PLA", `${fixed(b.pla_c, 1, " °C")} (target ${fixed(b.pla_target_c, 0, " °C")})`],
      ["CCF", `${fixed(b.ccf_c, 1, " °C")} (target ${fixed(b.ccf_target_c, 0, " °C")})`],
    ])),
    el("section", { class: "card" }, el("h2", {}, "Robot"), kv([
      ["I/O link", el("span", { class: "state", id: "robot-state" }, r.io || "–")],
      ["running", r.running ? "yes" : "no"],
      ["event", el("span", { id: "robot-event" }, r.event ?? "–")],
      ["heartbeat", r.heartbeat ? "ok" : "missing"],
      ["fault", r.fault || "none"],
    ])),
    el("section", { class: "card" }, el("h2", {}, "Sync"), kv([
      ["job", status.job ? el("a", { href: `#/job/${status.job}` }, `job ${status.job}`) : "none"],
      ["latency [ms]", latency(sync, "latency_ms")],
      ["cut position error [mm]", latency(sync, "cut_error_mm")],
      ["simulated", status.simulated ? `yes (time scale ${status.time_scale})` : "no"],
    ])),
  );
}

function makePlot(container, history) {
  if (typeof window.uPlot === "undefined") return null;
  const width = Math.max(300, container.clientWidth - 20);
  const series = [
    {},
    { label: "PLA °C", stroke: "#1f5fbf", width: 2 },
    { label: "PLA target", stroke: "#1f5fbf", dash: [6, 4] },
    { label: "CCF °C", stroke: "#d62728", width: 2 },
    { label: "CCF target", stroke: "#d62728", dash: [6, 4] },
  ];
  return new window.uPlot({ width, height: 300, series, scales: { x: { time: true } },
                            axes: [{}, { label: "°C" }] }, history.columns, container);
}

export function render(main, { rpc, history }) {
  const status = history.last || {};
  const plotBox = el("section", { class: "card", id: "temperature-plot" }, el("h2", {}, "Hotends, last 30 minutes"));
  const detailBox = el("div", { id: "cell-details" }, details(status));
  const message = el("p", { class: "error", id: "estop-message", role: "alert" });
  const estop = el("button", {
    class: "estop", id: "estop",
    onclick: async () => {
      if (!confirm("Emergency stop: send M112 to the board and abort the robot's program?\n" +
                   "This is not a safety function; the cell's own E-stop is.")) return;
      try {
        const r = await rpc.call("cell.estop");
        message.textContent = r.note || "E-stop sent";
      } catch (e) {
        message.textContent = errorText(e);
      }
    },
  }, "E-STOP");
  main.append(el("div", { class: "cards" }, el("section", { class: "card" }, el("h2", {}, "Emergency stop"), estop, message)),
              el("p"), detailBox, el("p"), plotBox);
  plot = makePlot(plotBox, history);
  if (!plot) plotBox.append(el("p", { class: "muted" }, "no chart library: the temperatures are in the header and above"));
  resizeObserver = new ResizeObserver(() => { if (plot) plot.setSize({ width: Math.max(300, plotBox.clientWidth - 20), height: 300 }); });
  resizeObserver.observe(plotBox);
  unsubscribe = rpc.on("notify.cell_status", (s) => {
    detailBox.replaceChildren(details(s));
    if (plot) plot.setData(history.columns);
  });
}

export function leave() {
  if (unsubscribe) unsubscribe();
  if (resizeObserver) resizeObserver.disconnect();
  if (plot) plot.destroy();
  plot = null;
}
