// The assessed curves of an alignment or a route, held off the page's main thread (a dedicated worker), so that a
// result of any size -- a million curves -- never blocks the page: the worker reads the rows (posted by the page, or
// fetched here as the job's CSV result and parsed here), orders and filters them, and answers the page with the few
// rows on screen, the counts, and the rows of the printout. Every message {id, op, ...} is answered {id, ...} or
// {id, error}.

/** All the rows read; `order`: the indices of the rows the view shows, in the order it shows them. */
const store = { rows: [], order: new Uint32Array(0), names: null };

const isBlank = (v) => v === null || v === undefined || v === "";

/** One CSV value: quoted -> text; empty -> null; true/false; a number; else the text. */
function typed(text, quoted) {
  if (quoted) return text;
  if (text === "") return null;
  if (text === "true") return true;
  if (text === "false") return false;
  const n = Number(text);
  return Number.isNaN(n) ? text : n;
}

/**
 * The rows of the service's CSV answer (app/jobs/csv_columns.py: a header, values quoted when they are text, RFC 4180
 * doubled quotes), as objects keyed by the header's names.
 */
export function parseCsv(text) {
  const rows = [];
  const n = text.length;
  let header = null;
  let record = [];
  let i = text.charCodeAt(0) === 0xfeff ? 1 : 0;
  const endRecord = () => {
    if (!header) header = record.map(String);
    else if (record.length > 1 || record[0] !== null) {
      const row = {};
      for (let k = 0; k < header.length; k += 1) row[header[k]] = record[k] ?? null;
      rows.push(row);
    }
    record = [];
  };
  while (i < n) {
    let value;
    if (text.charCodeAt(i) === 34) {
      // a quoted field: up to the quote not doubled
      let out = "";
      let from = i + 1;
      for (;;) {
        const q = text.indexOf('"', from);
        if (q < 0) throw new Error("the CSV answer ends inside a quoted value");
        out += text.slice(from, q);
        if (text.charCodeAt(q + 1) === 34) {
          out += '"';
          from = q + 2;
        } else {
          i = q + 1;
          break;
        }
      }
      value = typed(out, true);
    } else {
      let j = i;
      while (j < n) {
        const c = text.charCodeAt(j);
        if (c === 44 || c === 10 || c === 13) break;
        j += 1;
      }
      value = typed(text.slice(i, j), false);
      i = j;
    }
    record.push(value);
    const c = text.charCodeAt(i);
    if (c === 44) i += 1;
    else {
      if (c === 13) i += 1;
      if (text.charCodeAt(i) === 10) i += 1;
      endRecord();
    }
  }
  if (record.length) endRecord();
  return rows;
}

/** The curves' names in road order: C1, C2, ... by station where the rows have stations, else in file order. */
function nameCurves(rows) {
  const byVehicle = new Map();
  rows.forEach((r, i) => {
    const v = r.vehicle_index ?? 0;
    if (!byVehicle.has(v)) byVehicle.set(v, []);
    byVehicle.get(v).push(i);
  });
  for (const indices of byVehicle.values()) {
    const stationed = indices.every((i) => typeof rows[i].station_m === "number");
    if (stationed) indices.sort((a, b) => rows[a].station_m - rows[b].station_m || a - b);
    indices.forEach((i, k) => {
      rows[i].name = `C${k + 1}`;
      rows[i].road_order = k;
    });
  }
}

/** Counts over the rows of one vehicle (all of them, whatever the view shows). */
function stats(vehicle) {
  const out = { curves: 0, flagged: 0, refused: 0, below_standard_min_radius: 0, min_margin_kmh: null, min_safe_speed_kmh: null, worst: null, keys: [], devices: {}, warnings: 0, advised: 0 };
  const unseen = new Set(store.rows.slice(0, 100).flatMap((r) => Object.keys(r))); // fields with no value yet
  const keys = new Set();
  for (const r of store.rows) {
    if (vehicle !== null && vehicle !== undefined && (r.vehicle_index ?? 0) !== vehicle) continue;
    out.curves += 1;
    if (r.flagged) out.flagged += 1;
    if (!isBlank(r.error)) out.refused += 1;
    if (r.meets_standard_min_radius === false) out.below_standard_min_radius += 1;
    // the signs to post: curves per device, and the W1-13 warnings
    if (typeof r.advisory_speed_kmh === "number") out.advised += 1;
    if (r.truck_rollover_warning === true) out.warnings += 1;
    if (!isBlank(r.treatment_devices)) for (const d of String(r.treatment_devices).split("; ")) out.devices[d] = (out.devices[d] || 0) + 1;
    if (typeof r.margin_kmh === "number" && (out.min_margin_kmh === null || r.margin_kmh < out.min_margin_kmh)) {
      out.min_margin_kmh = r.margin_kmh;
      out.worst = { id: r.id, name: r.name, station_m: r.station_m ?? null, margin_kmh: r.margin_kmh };
    }
    if (typeof r.safe_speed_kmh === "number" && (out.min_safe_speed_kmh === null || r.safe_speed_kmh < out.min_safe_speed_kmh)) {
      out.min_safe_speed_kmh = r.safe_speed_kmh;
    }
    if (unseen.size) {
      for (const k of unseen) {
        if (!isBlank(r[k])) {
          keys.add(k);
          unseen.delete(k);
        }
      }
    }
  }
  // the columns that carry a value in any row (an error far down the file shows its column)
  out.keys = [...keys];
  return out;
}

/** The default order: the flagged curves first, worst (smallest margin) first, then the others in road order. */
function worstFirst(a, b) {
  const ra = store.rows[a];
  const rb = store.rows[b];
  if (Boolean(ra.flagged) !== Boolean(rb.flagged)) return ra.flagged ? -1 : 1;
  if (ra.flagged) {
    const ma = typeof ra.margin_kmh === "number" ? ra.margin_kmh : Infinity;
    const mb = typeof rb.margin_kmh === "number" ? rb.margin_kmh : Infinity;
    if (ma !== mb) return ma - mb;
  }
  return (ra.road_order ?? a) - (rb.road_order ?? b) || a - b;
}

const collator = new Intl.Collator(undefined, { numeric: true });

/** A column's order: blanks last whichever the direction; numbers as numbers, text in natural order (C2 < C10). */
function byKey(key, direction) {
  const sign = direction === "descending" ? -1 : 1;
  const sortKey = key === "name" ? "road_order" : key;
  return (a, b) => {
    const x = store.rows[a][sortKey];
    const y = store.rows[b][sortKey];
    if (x === y) return a - b;
    if (isBlank(x)) return 1;
    if (isBlank(y)) return -1;
    const order = typeof x === "number" && typeof y === "number" ? x - y : collator.compare(String(x), String(y));
    return sign * order || a - b;
  };
}

/**
 * Whether a row passes the filter: {flagged: true} (only flagged curves), {signed: true} (curves whose treatment
 * calls for a device), {warning: true} (curves with a W1-13 truck rollover warning), {text} (in its id or name, any
 * case).
 */
function passes(r, filter, vehicle) {
  if (vehicle !== null && vehicle !== undefined && (r.vehicle_index ?? 0) !== vehicle) return false;
  if (filter.flagged && !r.flagged) return false;
  if (filter.signed && isBlank(r.treatment_devices)) return false;
  if (filter.warning && r.truck_rollover_warning !== true) return false;
  if (filter.text) {
    const needle = filter.text.toLowerCase();
    if (!`${r.name ?? ""} ${r.id ?? ""}`.toLowerCase().includes(needle)) return false;
  }
  return true;
}

function view({ sort = null, filter = {}, vehicle = null }) {
  const kept = [];
  for (let i = 0; i < store.rows.length; i += 1) if (passes(store.rows[i], filter, vehicle)) kept.push(i);
  kept.sort(sort ? byKey(sort.key, sort.direction) : worstFirst);
  store.order = Uint32Array.from(kept);
  return { count: store.order.length };
}

function slice({ start, end }) {
  const rows = [];
  for (let i = Math.max(0, start); i < Math.min(end, store.order.length); i += 1) rows.push(store.rows[store.order[i]]);
  return { rows };
}

/**
 * The rows of the printout for one vehicle: every flagged curve, worst first, up to `max`; then, when all of the
 * flagged ones are printed and room is left, the others in road order. The counts say what was left to the CSV.
 */
function printRows({ max, vehicle = null }) {
  const mine = [];
  for (let i = 0; i < store.rows.length; i += 1) if (passes(store.rows[i], {}, vehicle)) mine.push(i);
  mine.sort(worstFirst);
  const flagged = mine.filter((i) => store.rows[i].flagged).length;
  const printed = mine.slice(0, max);
  const printedFlagged = Math.min(flagged, printed.length);
  return { rows: printed.map((i) => store.rows[i]), flagged, others: mine.length - flagged, printedFlagged, printedOthers: printed.length - printedFlagged };
}

async function fetchCsv({ url, key }) {
  const headers = { Accept: "text/csv" };
  if (key) headers.Authorization = `Bearer ${key}`;
  const response = await fetch(url, { headers, credentials: "omit" });
  if (!response.ok) {
    let problem = { status: response.status, title: response.statusText || `HTTP ${response.status}` };
    try {
      problem = await response.json();
    } catch {
      /* not a problem document */
    }
    throw Object.assign(new Error(problem.detail || problem.title), { problem });
  }
  return parseCsv(await response.text());
}

/**
 * A JSON answer's sign fields as the CSV answer writes them (docs/advisory.md, section 4): `treatment.devices` ->
 * `treatment_devices` (joined by "; ", null when none), `truck_rollover_warning.recommended` -> a boolean. Their long
 * source texts are stated once in the answer's `advisory`, not per row.
 */
function flatten(rows) {
  for (const r of rows) {
    const t = r.treatment;
    if (t && typeof t === "object") {
      r.treatment_devices = Array.isArray(t.devices) && t.devices.length ? t.devices.join("; ") : null;
      delete r.treatment;
    } else if (typeof r.treatment_devices === "string") {
      r.treatment_devices = r.treatment_devices.split(";").map((d) => d.trim()).filter(Boolean).join("; ") || null;
    }
    const w = r.truck_rollover_warning;
    if (w && typeof w === "object") r.truck_rollover_warning = w.recommended ?? null;
  }
}

/**
 * The head of a job's JSON result: the answer up to its `vehicles` list (`reading`, `advisory`, ...), which the
 * service writes first (app/alignments/rows.py, json_head). The stream is read until `,"vehicles":[` and cancelled:
 * the rows of a million curves are never read here. Inside a JSON string a quote is escaped, so that sequence can
 * only be the member's start.
 */
async function fetchHead({ url, key }) {
  const headers = { Accept: "application/json" };
  if (key) headers.Authorization = `Bearer ${key}`;
  const response = await fetch(url, { headers, credentials: "omit" });
  if (!response.ok || !response.body) return { head: null };
  const reader = response.body.getReader();
  const decoder = new TextDecoder();
  const marker = ',"vehicles":[';
  let text = "";
  try {
    while (text.length < 4_000_000) {
      const { value, done } = await reader.read();
      if (value) text += decoder.decode(value, { stream: true });
      const at = text.indexOf(marker);
      if (at >= 0) return { head: JSON.parse(`${text.slice(0, at)}}`) };
      if (done) return { head: JSON.parse(text) };
    }
    return { head: null };
  } finally {
    reader.cancel().catch(() => undefined);
  }
}

function load(rows, vehicle) {
  flatten(rows);
  store.rows = rows;
  nameCurves(rows);
  // a fleet's CSV: each vehicle's index, preset or saved id
  const vehicles = [];
  for (const r of rows) {
    if (typeof r.vehicle_index === "number" && !vehicles[r.vehicle_index]) {
      vehicles[r.vehicle_index] = { preset: r.vehicle_preset, saved_vehicle_id: r.vehicle_saved_id };
    }
  }
  return { total: rows.length, stats: { ...stats(vehicle), vehicles } };
}

const OPERATIONS = {
  load: ({ rows, vehicle }) => load(rows, vehicle),
  fetch: async (msg) => load(await fetchCsv(msg), msg.vehicle),
  head: fetchHead,
  stats: ({ vehicle }) => ({ stats: stats(vehicle) }),
  view,
  slice,
  print: printRows,
  // a request's JSON body, written here so that the page's thread never stringifies a large file
  encode: ({ value }) => ({ blob: new Blob([JSON.stringify(value)], { type: "application/json" }) }),
};

self.onmessage = async (event) => {
  const { id, op, ...msg } = event.data;
  try {
    self.postMessage({ id, ...(await OPERATIONS[op](msg)) });
  } catch (err) {
    self.postMessage({ id, error: { message: String(err.message || err), problem: err.problem || null } });
  }
};
