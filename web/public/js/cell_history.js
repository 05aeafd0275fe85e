// The cell's status over the last minutes, as columns for the temperature plots: time [s since
// the epoch], PLA actual/target, CCF actual/target (null where the board gave no reading).
export class CellHistory {
  constructor(seconds) {
    this.seconds = seconds;
    this.columns = [[], [], [], [], []];
    this.last = null;
  }

  add(status) {
    this.last = status;
    const b = status.board || {};
    const now = Date.now() / 1000;
    const row = [now, b.pla_c ?? null, b.pla_target_c ?? null, b.ccf_c ?? null, b.ccf_target_c ?? null];
    row.forEach((v, i) => this.columns[i].push(v));
    const cut = this.columns[0].findIndex((t) => t >= now - this.seconds);
    if (cut > 0) for (const c of this.columns) c.splice(0, cut);
  }
}
