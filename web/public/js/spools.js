// The spools on the Jobs page (docs/spools.md): each hotend's spool and what is left on it, and
// what the queued jobs' plans will take; live on notify.spools (and on the queue's changes, whose
// needs it shows). Loading a spool is the CLI's (`fibrecell spool load`) or spool.load's.
import { el, fixed, errorText } from "./ui.js";

function spoolRow(s, needs) {
  const need = s.role === "fibre" ? needs.fibre_m : needs.pla_m;
  const short = s.loaded && need > s.remaining_m;
  return el("tr", { dataset: { spool: s.tool } },
    el("td", {}, `${s.tool} (${s.role})`),
    el("td", {}, s.loaded ? `${s.material}${s.lot ? `, lot ${s.lot}` : ""}` : "no spool loaded (not checked)"),
    el("td", { class: short ? "state state-failed" : "", dataset: { remaining: s.loaded ? s.remaining_m : "" } },
       s.loaded ? `${fixed(s.remaining_m, 2)} m of ${fixed(s.loaded_m, 2)} m` : "–"),
    el("td", {}, `${fixed(need, 2)} m`));
}

export function spoolsCard(rpc) {
  const message = el("p", { class: "error", role: "alert" });
  const body = el("tbody", { id: "spool-rows" });
  const note = el("p", { id: "spools-note" });
  const card = el("section", { class: "card", id: "spools-card" },
    el("h2", {}, "Spools"), message,
    el("table", { class: "jobs" },
       el("thead", {}, el("tr", {}, ["hotend", "spool", "left", "the queue needs"].map((h) => el("th", {}, h)))),
       body),
    note);
  const draw = (list) => {
    body.replaceChildren(...list.spools.map((s) => spoolRow(s, list.queue_needs)));
    note.textContent = `A start needs the plan's figure + ${list.margin_percent}% + ${list.margin_m} m ` +
                       `(spools.check: ${list.check}).` + (list.note ? ` ${list.note}` : "");
  };
  const refresh = async () => {
    try {
      draw(await rpc.call("spool.list"));
      message.textContent = "";
    } catch (e) {
      message.textContent = errorText(e);
    }
  };
  return { card, draw, refresh };
}
