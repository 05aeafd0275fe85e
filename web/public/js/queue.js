// The print queue and the bed on the Jobs page (docs/queue.md): whose part is on the bed and the
// button that says it is clear, the queued jobs in order with up, down and out, and next / pause /
// resume. The service decides: a refused action shows its own reason.
import { el, errorText } from "./ui.js";

async function call(rpc, message, method, params = {}) {
  message.textContent = "";
  try {
    return await rpc.call(method, params);
  } catch (e) {
    message.textContent = errorText(e);
    return null;
  }
}

function bedLine(bed) {
  if (!bed || bed.clear) return el("span", { class: "state state-completed", id: "bed-state" }, "bed clear");
  const who = bed.job ? `job ${bed.job}${bed.name ? ` (${bed.name})` : ""} ${bed.outcome}` : "not known";
  return el("span", { class: "state state-paused", id: "bed-state" }, `bed not clear: ${who}`);
}

function row(rpc, message, entry, count) {
  const move = (to) => call(rpc, message, "queue.move", { job: entry.id, position: to });
  return el("tr", { dataset: { queued: entry.id } },
    el("td", {}, String(entry.position)),
    el("td", {}, el("a", { href: `#/job/${entry.id}` }, String(entry.id))),
    el("td", {}, entry.name || ""),
    el("td", {}, entry.state),
    el("td", { class: "actions" },
      el("button", { dataset: { action: "up" }, disabled: entry.position === 1, title: "print it earlier",
                     onclick: () => move(entry.position - 1) }, "↑"),
      el("button", { dataset: { action: "down" }, disabled: entry.position === count, title: "print it later",
                     onclick: () => move(entry.position + 1) }, "↓"),
      el("button", { dataset: { action: "unqueue" }, title: "take it out of the queue (the job stays)",
                     onclick: () => call(rpc, message, "queue.remove", { job: entry.id }) }, "out")));
}

// The card: drawn again from every queue.list answer or notify.queue.
export function queueCard(rpc) {
  const message = el("p", { class: "error", id: "queue-message", role: "alert" });
  const body = el("div", { id: "queue-body" });
  const card = el("section", { class: "card", id: "queue-card" }, el("h2", {}, "Queue"), body, message);
  const draw = (q) => {
    const jobs = q.jobs || [];
    const mode = q.auto_start === "after_clear" ? "the next job starts once the bed is cleared" : "jobs start with “next”";
    body.replaceChildren(
      el("p", {}, bedLine(q.bed), " ",
        el("button", { id: "clear-cell", class: "primary", disabled: !q.bed || q.bed.clear,
                       title: "the part is off the bed: jobs may start again",
                       onclick: () => call(rpc, message, "cell.clear") }, "Bed is clear")),
      el("p", { class: "muted", id: "queue-mode" }, mode,
        q.paused ? el("strong", { id: "queue-paused" }, ` · paused${q.paused_reason ? `: ${q.paused_reason}` : ""}`) : null),
      jobs.length === 0 ? el("p", { class: "muted", id: "queue-empty" }, "No job is queued: “queue” on a planned job adds it.")
        : el("table", { id: "queue-table" },
            el("thead", {}, el("tr", {}, ["#", "job", "name", "state", ""].map((h) => el("th", {}, h)))),
            el("tbody", {}, jobs.map((j) => row(rpc, message, j, jobs.length)))),
      el("p", { class: "actions" },
        el("button", { id: "queue-next", disabled: jobs.length === 0, onclick: () => call(rpc, message, "queue.next") }, "Start next"),
        " ",
        q.paused ? el("button", { id: "queue-resume", onclick: () => call(rpc, message, "queue.resume") }, "Resume queue")
                 : el("button", { id: "queue-pause", onclick: () => call(rpc, message, "queue.pause") }, "Pause queue")));
  };
  const refresh = async () => {
    const q = await call(rpc, message, "queue.list");
    if (q) draw(q);
  };
  return { card, draw, refresh };
}
