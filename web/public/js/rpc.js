// The socket API's JSON-RPC 2.0 over the dashboard's WebSocket (/api/ws): calls answered by id,
// notifications to listeners, subscriptions renewed after a reconnect (docs/dashboard.md).

export class RpcError extends Error {
  constructor(error) {
    super(error.message);
    this.code = error.code;
    this.data = error.data;
  }
}

export class Rpc {
  constructor() {
    this.nextId = 1;
    this.pending = new Map();     // id -> {resolve, reject}
    this.listeners = new Map();   // notification method -> Set of functions
    this.topics = new Set();      // what we subscribed to, renewed on reconnect
    this.stateListeners = new Set();
    this.ws = null;
    this.backoffMs = 500;
    this.closedByUs = false;
  }

  // state: "connecting", "open", "closed" (will retry), "unauthorized" (log in again)
  onState(fn) { this.stateListeners.add(fn); }
  setState(state) { for (const fn of this.stateListeners) fn(state); }

  connect() {
    this.closedByUs = false;
    this.setState("connecting");
    const scheme = location.protocol === "https:" ? "wss:" : "ws:";
    const ws = new WebSocket(`${scheme}//${location.host}/api/ws`);
    this.ws = ws;
    ws.onopen = () => {
      this.backoffMs = 500;
      this.setState("open");
      if (this.topics.size) this.send({ jsonrpc: "2.0", method: "subscribe", params: { topics: [...this.topics] } });
    };
    ws.onmessage = (ev) => this.receive(ev.data);
    ws.onclose = async () => {
      for (const { reject } of this.pending.values()) reject(new Error("the connection to fibrecelld closed"));
      this.pending.clear();
      if (this.closedByUs || this.ws !== ws) return;
      // A refused upgrade looks like any close: ask whether the login is still good.
      const session = await fetch("api/session").then((r) => r.json()).catch(() => null);
      if (session && !session.authenticated) {
        this.setState("unauthorized");
        return;
      }
      this.setState("closed");
      setTimeout(() => { if (!this.closedByUs && this.ws === ws) this.connect(); }, this.backoffMs);
      this.backoffMs = Math.min(this.backoffMs * 2, 10000);
    };
  }

  close() {
    this.closedByUs = true;
    if (this.ws) this.ws.close();
    this.ws = null;
  }

  send(message) {
    if (!this.ws || this.ws.readyState !== WebSocket.OPEN) throw new Error("not connected to fibrecelld");
    this.ws.send(JSON.stringify(message));
  }

  call(method, params = {}) {
    return new Promise((resolve, reject) => {
      const id = this.nextId++;
      try {
        this.send({ jsonrpc: "2.0", id, method, params });
      } catch (e) {
        reject(e);
        return;
      }
      this.pending.set(id, { resolve, reject });
    });
  }

  on(method, fn) {
    if (!this.listeners.has(method)) this.listeners.set(method, new Set());
    this.listeners.get(method).add(fn);
    return () => this.listeners.get(method).delete(fn);
  }

  async subscribe(topics) {
    const fresh = topics.filter((t) => !this.topics.has(t));
    for (const t of fresh) this.topics.add(t);
    if (fresh.length && this.ws && this.ws.readyState === WebSocket.OPEN) await this.call("subscribe", { topics: fresh });
  }

  receive(text) {
    let message;
    try { message = JSON.parse(text); } catch { return; }
    for (const m of Array.isArray(message) ? message : [message]) {
      if (m.id !== undefined && m.id !== null && this.pending.has(m.id)) {
        const { resolve, reject } = this.pending.get(m.id);
        this.pending.delete(m.id);
        if (m.error) reject(new RpcError(m.error)); else resolve(m.result);
      } else if (m.method) {
        for (const fn of this.listeners.get(m.method) || []) fn(m.params);
      }
    }
  }
}
