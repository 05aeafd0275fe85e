// The Log page: the service's log lines live (topic "log", info and above), filterable by level.
import { el } from "./ui.js";

const order = ["info", "warning", "error", "critical"];
let unsubscribe = null;

function line(l) {
  return el("div", { class: l.level }, `${l.time} ${l.level.padEnd(8)} ${l.text}`);
}

export function render(main, { rpc, logLines }) {
  const select = el("select", { id: "log-level" }, order.map((l) => el("option", { value: l }, `${l} and above`)));
  const text = el("input", { type: "search", id: "log-filter", placeholder: "filter text" });
  const box = el("div", { class: "log-lines", id: "log-lines" });
  const shown = (l) => order.indexOf(l.level) >= order.indexOf(select.value) &&
                       (!text.value || l.text.toLowerCase().includes(text.value.toLowerCase()));
  const redraw = () => box.replaceChildren(...logLines.filter(shown).map(line));
  select.addEventListener("change", redraw);
  text.addEventListener("input", redraw);
  main.append(el("div", {}, select, " ", text), el("p"), box);
  redraw();
  unsubscribe = rpc.on("notify.log", (l) => {
    if (!shown(l)) return;
    const atBottom = box.scrollTop + box.clientHeight >= box.scrollHeight - 5;
    box.append(line(l));
    if (atBottom) box.scrollTop = box.scrollHeight;
  });
}

export function leave() {
  if (unsubscribe) unsubscribe();
}
