// The dashboard's shell: the login, the connection, the at-a-glance header and the pages
// (#/cell, #/jobs, #/job/ID, #/history, #/log). Every page talks to fibrecelld through one Rpc.
import { Rpc } from "./rpc.js";
import { CellHistory } from "./cell_history.js";
import * as cellPage from "./cell.js";
import * as jobsPage from "./jobs.js";
import * as jobPage from "./job.js";
import * as historyPage from "./history.js";
import * as logPage from "./log.js";
import { formatDuration, el } from "./ui.js";

const rpc = new Rpc();
const history = new CellHistory(30 * 60);  // the last 30 minutes of cell status
const logLines = [];                       // the log page's lines, kept while on other pages
let current = null;                        // the page shown: {module, args}

const ctx = { rpc, history, logLines };

function setLink(state) {
  const link = document.getElementById("link");
  const text = { connecting: "connecting", open: "connected", closed: "reconnecting", unauthorized: "logged out" }[state];
  link.textContent = text;
  link.className = "pill " + (state === "open" ? "ok" : state === "connecting" ? "" : "bad");
  if (state === "unauthorized") showLogin("Your session ended: log in again.");
  if (state === "open") onConnected();
}

function glance(status) {
  document.getElementById("cell-name").textContent = status.name || "";
  const p = status.progress;
  document.getElementById("glance-layer").textContent = p ? `layer ${p.layer}/${p.layers}` : "idle";
  document.getElementById("glance-eta").textContent = p && p.eta_s !== undefined ? `ETA ${formatDuration(p.eta_s)}` : "";
  const b = status.board || {};
  const t = (v, target) => (v === undefined ? "–" : `${v.toFixed(0)}°` + (target ? ` / ${target.toFixed(0)}°` : ""));
  document.getElementById("glance-pla").textContent = `PLA ${t(b.pla_c, b.pla_target_c)}`;
  document.getElementById("glance-ccf").textContent = `CCF ${t(b.ccf_c, b.ccf_target_c)}`;
  // Why the hotends are on (cell.status heaters: docs/service.md, "Heaters").
  const h = status.heaters || {};
  const off = h.off_in_s === null || h.off_in_s === undefined ? "" : `, off in ${formatDuration(h.off_in_s)}`;
  const heaters = document.getElementById("glance-heaters");
  heaters.textContent = heaters.title = h.on ? `heaters on: ${h.why}${off}` : "heaters off";  // the title: when cut
}

// A page rendered on the connection that is open now (its subscriptions are this connection's).
let routedSinceOpen = false;

async function onConnected() {
  routedSinceOpen = false;
  try {
    await rpc.subscribe(["cell", "log"]);
    const status = await rpc.call("cell.status");
    history.add(status);
    glance(status);
  } catch (e) {
    console.warn(e);
  }
  // A page the user went to while the status came rendered on this connection already: rendering
  // it again would throw away what was begun in it (a half-filled submit form).
  if (!routedSinceOpen) route();
}

rpc.on("notify.cell_status", (status) => {
  history.add(status);
  glance(status);
});
rpc.on("notify.log", (line) => {
  logLines.push(line);
  if (logLines.length > 5000) logLines.splice(0, logLines.length - 5000);
});

function route() {
  routedSinceOpen = true;
  const [, name = "cell", arg] = location.hash.split("/");
  const module = { cell: cellPage, jobs: jobsPage, job: jobPage, history: historyPage, log: logPage }[name] || cellPage;
  for (const a of document.querySelectorAll("nav a"))
    a.classList.toggle("active", a.dataset.page === name || (name === "job" && a.dataset.page === "jobs"));
  if (current && current.module.leave) current.module.leave();
  const main = document.getElementById("page");
  main.replaceChildren();
  current = { module, arg };
  module.render(main, ctx, arg);
}

function showLogin(message) {
  const dialog = document.getElementById("login-dialog");
  document.getElementById("login-error").textContent = message || "";
  if (!dialog.open) dialog.showModal();
  document.getElementById("login-token").focus();
}

async function login(token) {
  const res = await fetch("api/login", {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ token }),
  });
  const body = await res.json().catch(() => ({}));
  if (!res.ok) throw new Error(body.error || `login refused (${res.status})`);
}

document.getElementById("login-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  const input = document.getElementById("login-token");
  try {
    await login(input.value);
    input.value = "";
    document.getElementById("login-dialog").close();
    rpc.connect();
  } catch (e) {
    document.getElementById("login-error").textContent = e.message;
  }
});

document.getElementById("logout").addEventListener("click", async () => {
  rpc.close();
  await fetch("api/logout", { method: "POST" });
  document.getElementById("page").replaceChildren(el("p", { class: "muted" }, "Logged out."));
  setLink("unauthorized");
});

window.addEventListener("hashchange", () => { if (rpc.ws && rpc.ws.readyState === WebSocket.OPEN) route(); });
rpc.onState(setLink);

(async () => {
  if (typeof window.uPlot === "undefined")
    document.getElementById("page").before(el("p", { class: "notice" },
      "The chart library is missing (web/node_modules not installed: run tools/setup.sh); temperatures show as numbers only."));
  const session = await fetch("api/session").then((r) => r.json()).catch(() => ({ authenticated: false }));
  if (session.authenticated) rpc.connect();
  else showLogin();
})();
