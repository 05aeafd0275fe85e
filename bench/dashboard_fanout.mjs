// Notification fan-out to dashboards (docs/dashboard.md, "Benchmark"): fibrecelld (Release) prints
// the tensile bar at time scale 120 twice, once watched by nobody and once by N dashboard
// WebSocket clients (each logged in, subscribed to "*" as the pages are: the cell, the job, the
// log). Reported: the updates each client received per second (min / median / max), the
// service's CPU over the print, and the sync engine's latency p99 per event kind (result.json).
//
//   node bench/dashboard_fanout.mjs --fibrecelld build/release/daemon/fibrecelld [--clients 20]
import { spawn } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { createRequire } from "node:module";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const root = resolve(dirname(fileURLToPath(import.meta.url)), "..");
const WebSocket = createRequire(join(root, "web/package.json"))("ws");
const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) =>
  a.startsWith("--") ? [...pairs, [a.slice(2), all[i + 1]]] : pairs, []));
const fibrecelld = args.fibrecelld || join(root, "build/release/daemon/fibrecelld");
const clientCount = Number(args.clients || 20);
const token = "fanout-bench-token-0123456789";
const example = join(root, "examples/tensile-bar");
const ticks = 100;  // USER_HZ: the unit of /proc/PID/stat's times on Linux

function cpuSeconds(pid) {
  const fields = readFileSync(`/proc/${pid}/stat`, "utf8").split(") ")[1].split(" ");
  return (Number(fields[11]) + Number(fields[12])) / ticks;  // utime + stime
}

async function startService(dir) {
  writeFileSync(join(dir, "cell.yaml"), [
    "name: fanout-bench", "log_level: info", `state_dir: ${join(dir, "state")}`, "simulated: true",
    "simulation: {time_scale: 120, hotend_tau_s: 2, residency_s: 0.5}",
    "robot_io: {stable_reads: 1, heartbeat_period_ms: 20}",
    "api:", `  socket: ${join(dir, "api.sock")}`,
    `  http: {enabled: true, port: 0, token: ${token}}`, "jobs: {planner_threads: 1}", ""].join("\n"));
  const child = spawn(fibrecelld, ["--config", join(dir, "cell.yaml")], { stdio: ["ignore", "pipe", "ignore"] });
  const port = await new Promise((res, rej) => {
    let text = "";
    child.stdout.on("data", (c) => {
      text += c;
      const m = text.match(/dashboard on http:\/\/127\.0\.0\.1:(\d+)\//);
      if (m) res(Number(m[1]));
    });
    child.on("exit", (code) => rej(new Error(`fibrecelld exited ${code}`)));
  });
  return { child, port };
}

async function cookieFor(port) {
  const res = await fetch(`http://127.0.0.1:${port}/api/login`, { method: "POST", body: JSON.stringify({ token }) });
  if (!res.ok) throw new Error(`login: ${res.status}`);
  return res.headers.get("set-cookie").split(";")[0];
}

// One dashboard-like client: counts every notification it gets.
function watch(port, cookie) {
  return new Promise((res, rej) => {
    const ws = new WebSocket(`ws://127.0.0.1:${port}/api/ws`, { headers: { Cookie: cookie } });
    const client = { ws, received: 0, next: 1, pending: new Map() };
    client.call = (method, params = {}) => new Promise((ok, fail) => {
      const id = client.next++;
      client.pending.set(id, { ok, fail });
      ws.send(JSON.stringify({ jsonrpc: "2.0", id, method, params }));
    });
    ws.on("message", (data) => {
      const m = JSON.parse(data);
      if (m.id && client.pending.has(m.id)) {
        const p = client.pending.get(m.id);
        client.pending.delete(m.id);
        if (m.error) p.fail(new Error(m.error.message)); else p.ok(m.result);
      } else if (m.method) client.received++;
    });
    ws.on("open", () => res(client));
    ws.on("error", rej);
  });
}

async function run(watchers) {
  const dir = mkdtempSync(join(tmpdir(), "fanout-"));
  const { child, port } = await startService(dir);
  try {
    const control = await watch(port, await cookieFor(port));
    const clients = [];
    for (let i = 0; i < watchers; ++i) {
      const c = await watch(port, await cookieFor(port));
      await c.call("subscribe", { topics: ["*"] });
      clients.push(c);
    }
    await control.call("subscribe", { topics: ["*"] });
    const files = { "tensile-bar.msh": readFileSync(join(example, "tensile-bar.msh")).toString("base64") };
    const job = await control.call("job.submit", {
      job_yaml: readFileSync(join(example, "tensile-bar.job.yaml"), "utf8"), files, start: false });
    for (;;) {  // planned
      const j = await control.call("job.get", { job: job.id });
      if (j.state === "planned") break;
      if (j.state === "failed") throw new Error(j.reason);
      await new Promise((r) => setTimeout(r, 100));
    }
    for (const c of clients) c.received = 0;
    const cpu0 = cpuSeconds(child.pid), t0 = performance.now();
    await control.call("job.start", { job: job.id });
    let done;
    for (;;) {
      done = await control.call("job.get", { job: job.id });
      if (["completed", "completed_with_warnings", "failed", "aborted"].includes(done.state)) break;
      await new Promise((r) => setTimeout(r, 200));
    }
    const seconds = (performance.now() - t0) / 1000, cpu = cpuSeconds(child.pid) - cpu0;
    const rates = clients.map((c) => c.received / seconds).sort((a, b) => a - b);
    for (const c of [control, ...clients]) c.ws.close();
    return { watchers, state: done.state, seconds, cpu, rates, latency: done.result?.latency_ms || {} };
  } finally {
    child.kill("SIGTERM");
    await new Promise((r) => child.on("exit", r));
    rmSync(dir, { recursive: true, force: true });
  }
}

const fmt = (v, d = 2) => (typeof v === "number" ? v.toFixed(d) : "-");
const rows = [await run(0), await run(clientCount)];
console.log(`dashboard fan-out: the tensile bar at time scale 120, ${clientCount} WebSocket clients subscribed to "*"`);
console.log("| clients | print | wall s | service CPU s | CPU % of one core | updates/s per client (min / median / max) | sync latency p99 ms (extrude_on / fibre_start / cut) |");
console.log("|---|---|---|---|---|---|---|");
for (const r of rows) {
  const rate = r.rates.length ? `${fmt(r.rates[0], 1)} / ${fmt(r.rates[r.rates.length >> 1], 1)} / ${fmt(r.rates.at(-1), 1)}` : "-";
  const l = r.latency;
  console.log(`| ${r.watchers} | ${r.state} | ${fmt(r.seconds, 1)} | ${fmt(r.cpu)} | ${fmt(100 * r.cpu / r.seconds, 1)} | ${rate} | ${fmt(l.extrude_on?.p99, 3)} / ${fmt(l.fibre_start?.p99, 3)} / ${fmt(l.cut?.p99, 3)} |`);
}
