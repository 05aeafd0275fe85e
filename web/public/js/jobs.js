// The Jobs page: the print queue and the bed (queue.js), the spools (spools.js), every job with
// its state, submitting a job (its YAML and the files it names, as `fibrecell submit` sends them), and the actions its
// state allows. The service decides: a refused action shows the service's own reason.
import { el, errorText } from "./ui.js";
import { queueCard } from "./queue.js";
import { spoolsCard } from "./spools.js";

// Which buttons a state shows (job_state.hpp has the one table; the service still checks).
export const actions = {
  planning: ["queue", "abort"],
  planned: ["start", "queue", "replan", "abort", "remove"],
  starting: ["abort"],
  printing: ["pause", "abort"],
  pausing: ["abort"],
  paused: ["resume", "abort"],
  interrupted: ["resume", "abort"],
  completed: ["remove"],
  completed_with_warnings: ["remove"],
  aborted: ["remove"],
  failed: ["replan", "remove"],
};

let jobs = new Map();
let unsubscribe = [];

export function stateBadge(job) {
  let text = job.state.replaceAll("_", " ");
  if (job.state === "planning" && job.planning) text += ` (${job.planning.stage} ${Math.round(100 * job.planning.fraction)}%)`;
  if (job.state === "printing" && job.print) text += ` (layer ${job.print.layer}/${job.print.layers})`;
  return el("span", { class: `state state-${job.state}`, dataset: { state: job.state } }, text);
}

export async function act(rpc, action, id, message) {
  message.textContent = "";
  if (action === "abort" && !confirm(`Abort job ${id}? This cannot be resumed.`)) return;
  if (action === "remove" && !confirm(`Remove job ${id} and its files?`)) return;
  try {
    if (action === "queue") await rpc.call("queue.add", { job: id });
    else await rpc.call(`job.${action}`, { job: id });
  } catch (e) {
    message.textContent = `job ${id}: ${errorText(e)}`;
  }
}

function row(rpc, job, message) {
  return el("tr", { dataset: { job: job.id } },
    el("td", {}, el("a", { href: `#/job/${job.id}` }, String(job.id))),
    el("td", {}, job.name),
    el("td", {}, stateBadge(job), job.reason ? el("div", { class: "muted" }, job.reason) : null),
    el("td", {}, job.plan ? `${job.plan.layers ?? "?"} layers` : ""),
    el("td", { class: "actions" }, (actions[job.state] || []).map((a) =>
      el("button", { class: a === "start" ? "primary" : a === "abort" ? "danger" : "", dataset: { action: a },
                     onclick: () => act(rpc, a, job.id, message) }, a))));
}

function table(rpc, message) {
  const sorted = [...jobs.values()].sort((a, b) => b.id - a.id);
  return el("table", { id: "jobs-table" },
    el("thead", {}, el("tr", {}, ["id", "name", "state", "plan", ""].map((h) => el("th", {}, h)))),
    el("tbody", {}, sorted.map((j) => row(rpc, j, message))));
}

function base64(buffer) {
  const bytes = new Uint8Array(buffer);
  let text = "";
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

function submitForm(rpc, onSubmitted) {
  const yaml = el("input", { type: "file", id: "submit-yaml", accept: ".yaml,.yml", required: true });
  const files = el("input", { type: "file", id: "submit-files", multiple: true });
  const start = el("input", { type: "checkbox", id: "submit-start" });
  const message = el("p", { id: "submit-message", role: "status" });
  const form = el("form", { class: "card", id: "submit-form" },
    el("h2", {}, "Submit a job"),
    el("label", {}, "Job file (YAML) ", yaml), el("br"),
    el("label", {}, "Its files (mesh, stress field) ", files), el("br"),
    el("label", {}, start, " start when planned"), el("br"),
    el("button", { type: "submit", class: "primary" }, "Submit"), message);
  form.addEventListener("submit", async (ev) => {
    ev.preventDefault();
    message.className = "";
    message.textContent = "sending…";
    try {
      const jobYaml = await yaml.files[0].text();
      const attached = {};
      for (const f of files.files) attached[f.name] = base64(await f.arrayBuffer());
      const job = await rpc.call("job.submit", { job_yaml: jobYaml, files: attached, start: start.checked });
      message.textContent = `job ${job.id} (${job.name}) submitted: planning`;
      form.reset();
      onSubmitted(job);
    } catch (e) {
      message.className = "error";
      message.textContent = errorText(e);
    }
  });
  return form;
}

export async function render(main, { rpc }) {
  const message = el("p", { class: "error", id: "jobs-message", role: "alert" });
  const holder = el("div", { id: "jobs-holder" });
  const redraw = () => holder.replaceChildren(table(rpc, message));
  const queue = queueCard(rpc);
  const spools = spoolsCard(rpc);
  main.append(submitForm(rpc, (job) => { jobs.set(job.id, job); redraw(); }), queue.card, spools.card,
              el("h2", {}, "Jobs"), message, holder);
  await rpc.subscribe(["*"]);  // every job's state changes, the queue's and the spools'
  unsubscribe.push(rpc.on("notify.queue", (q) => { queue.draw(q); spools.refresh(); }));
  unsubscribe.push(rpc.on("notify.spools", (list) => spools.draw(list)));
  await queue.refresh();
  await spools.refresh();
  unsubscribe.push(rpc.on("notify.job_state", (job) => {
    if (job.state === "removed") jobs.delete(job.id); else jobs.set(job.id, job);
    redraw();
  }));
  unsubscribe.push(rpc.on("notify.job_progress", (p) => {
    const job = jobs.get(p.job);
    if (!job) return;
    if (p.planning) job.planning = p.planning;
    if (p.print) job.print = p.print;
    redraw();
  }));
  try {
    jobs = new Map((await rpc.call("job.list")).map((j) => [j.id, j]));
  } catch (e) {
    message.textContent = errorText(e);
  }
  redraw();
}

export function leave() {
  for (const u of unsubscribe) u();
  unsubscribe = [];
}
