// Small DOM helpers: elements without innerHTML (the page runs under a strict Content-Security-Policy and
// never parses markup from strings, except the service's own SVG figures through DOMParser), number formats,
// downloads.

/** An element with attributes (`class`, `text`, data-*, aria-*, properties for `on*`) and children. */
export function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attrs)) {
    if (value === undefined || value === null || value === false) continue;
    if (name === "class") node.className = value;
    else if (name === "text") node.textContent = value;
    else if (name.startsWith("on") && typeof value === "function") node.addEventListener(name.slice(2), value);
    else node.setAttribute(name, value === true ? "" : String(value));
  }
  for (const child of children.flat()) {
    if (child === undefined || child === null || child === false) continue;
    node.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return node;
}

export const $ = (selector, root = document) => root.querySelector(selector);
export const $$ = (selector, root = document) => Array.from(root.querySelectorAll(selector));

export function clear(node) {
  while (node.firstChild) node.firstChild.remove();
  return node;
}

/** A number with `digits` decimals ("-" for null), e.g. fmt(0.33911, 3) -> "0.339". */
export function fmt(value, digits = 3) {
  if (value === null || value === undefined || Number.isNaN(value)) return "-";
  return Number(value).toFixed(digits);
}

const GROUPED = new Map(); // one formatter per number of decimals (making one per call is slow)

/** A number with `digits` decimals and thousands separators ("12,345.6"; "-" for null). */
export function grouped(value, digits = 0) {
  if (value === null || value === undefined || value === "") return "-";
  const n = Number(value);
  if (!Number.isFinite(n)) return String(value);
  if (!GROUPED.has(digits)) GROUPED.set(digits, new Intl.NumberFormat("en-US", { minimumFractionDigits: digits, maximumFractionDigits: digits }));
  return GROUPED.get(digits).format(n);
}

/** A number for prose, at most `digits` decimals and at least `least` ("0.35", "0.40", "0.355", "3.15"): never a
 * float's tail such as 0.9999999999999994. Text that is not a number is returned as it is. */
export function num(value, digits = 3, least = 0) {
  if (value === null || value === undefined || value === "") return "-";
  const n = Number(value);
  if (!Number.isFinite(n)) return String(value);
  let text = n.toFixed(digits);
  if (text.includes(".")) {
    text = text.replace(/0+$/, "");
    const decimals = text.split(".")[1].length;
    if (decimals < least) text += "0".repeat(least - decimals);
    text = text.replace(/\.$/, "");
  }
  return text === "-0" ? "0" : text;
}

/** A signed number: "+0.012" / "-0.011". */
export function signed(value, digits = 3) {
  if (value === null || value === undefined) return "-";
  const text = Math.abs(value).toFixed(digits);
  return (value < 0 && Number(text) !== 0 ? "\u2212" : "+") + text;
}

const SVG_NS = "http://www.w3.org/2000/svg";

/** The service's SVG text as an inline <svg> node: parsed as XML (scripts never run), anything active removed. */
export function svgNode(text) {
  const doc = new DOMParser().parseFromString(text, "image/svg+xml");
  const root = doc.documentElement;
  if (root.namespaceURI !== SVG_NS || root.localName !== "svg") throw new Error("not an SVG document");
  for (const bad of root.querySelectorAll("script, foreignObject, style")) bad.remove();
  for (const node of [root, ...root.querySelectorAll("*")]) {
    for (const attr of Array.from(node.attributes)) {
      const name = attr.name.toLowerCase();
      if (name.startsWith("on") || ((name === "href" || name === "xlink:href") && !attr.value.startsWith("#"))) {
        node.removeAttribute(attr.name);
      }
    }
  }
  const svg = document.importNode(root, true);
  const title = svg.querySelector("title");
  svg.setAttribute("role", "img");
  if (title) svg.setAttribute("aria-label", title.textContent.trim());
  svg.removeAttribute("width");
  svg.removeAttribute("height");
  return svg;
}

export function svgEl(tag, attrs = {}) {
  const node = document.createElementNS(SVG_NS, tag);
  for (const [name, value] of Object.entries(attrs)) node.setAttribute(name, String(value));
  return node;
}

/** Offer a Blob as a file download. */
export function download(filename, blob) {
  const url = URL.createObjectURL(blob);
  const a = el("a", { href: url, download: filename });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** A table: `columns` [{key, label, format?, text?}], `rows` objects; returns the <table>. */
export function table(columns, rows, { caption, rowClass } = {}) {
  const cls = (c) => (c.nowrap ? "nowrap" : c.text ? "text" : null); // nowrap: a short word, left-aligned
  const head = el("tr", {}, columns.map((c) => el("th", { scope: "col", class: cls(c) }, c.label)));
  const body = rows.map((row) =>
    el(
      "tr",
      { class: rowClass ? rowClass(row) : null },
      columns.map((c) => el("td", { class: cls(c) }, c.format ? c.format(row[c.key], row) : row[c.key] ?? "-")),
    ),
  );
  return el("table", {}, caption ? el("caption", { class: "hint" }, caption) : null, el("thead", {}, head), el("tbody", {}, body));
}

/** Wide boxes are watched for overflow: each shows its scroll cue only while its table is wider than it. */
const overflowWatch = typeof ResizeObserver === "undefined" ? null : new ResizeObserver((entries) => {
  for (const { target } of entries) {
    const box = target.closest(".table-wrap");
    const cue = box?.previousElementSibling;
    if (cue?.classList.contains("scroll-cue")) cue.hidden = box.scrollWidth <= box.clientWidth + 1;
  }
});

/** A cue in words put before a scrolling box, shown while its content is wider than it. */
export function scrollCue(box) {
  const cue = el("p", { class: "scroll-cue", hidden: true, "aria-hidden": "true" }, "\u2194 More columns: scroll the table sideways.");
  overflowWatch?.observe(box);
  if (box.firstElementChild) overflowWatch?.observe(box.firstElementChild);
  return cue;
}

/** A horizontally scrollable, keyboard-focusable region around a wide table, with a cue in words shown when the
 * table is wider than the region (no column is hidden without saying so). */
export function scroller(label, child, tall = false) {
  const box = el("div", { class: tall ? "table-wrap tall" : "table-wrap", tabindex: "0", role: "region", "aria-label": label }, child);
  return el("div", { class: "scroll-box" }, scrollCue(box), box);
}

/** The page's own wide regions (written in its HTML) get their cue too. */
export function cueStaticTables(root = document) {
  for (const box of $$(".table-wrap", root)) {
    if (box.parentElement.classList.contains("scroll-box")) continue;
    box.before(scrollCue(box));
  }
}

const UNITS = [
  ["_kmh", "km/h"],
  ["_kn_per_m", "kN/m"],
  ["_kn", "kN"],
  ["_kg", "kg"],
  ["_percent", "%"],
  ["_deg", "deg"],
  ["_m", "m"],
  ["_g", "g"],
  ["_s", "s"],
];

/** A label from an API field's name: `deflection_deg` -> "Deflection [deg]", `front_llt_ratio` -> "Front llt ratio";
 * `lower`: in lower case, for prose ("posted speed [km/h]"). */
export function fieldLabel(key, lower = false) {
  const name = String(key);
  const unit = UNITS.find(([suffix]) => name.endsWith(suffix) && name.length > suffix.length);
  const words = (unit ? name.slice(0, -unit[0].length) : name).replaceAll("_", " ");
  const text = lower ? words : words.charAt(0).toUpperCase() + words.slice(1);
  return unit ? `${text} [${unit[1]}]` : text;
}

/** A message with the API's field names in words: "has no superelevation_percent" -> "has no superelevation [%]"
 * (lower-case names joined by underscores; ids such as veh_... and flt_... are kept). */
export function plainWords(text) {
  return String(text).replace(/\b(?!(?:veh|flt|job)_)[a-z]+(?:_[a-z]+)+\b/g, (token) => fieldLabel(token, true));
}

/** Thousands separators in a number's text: "36210" -> "36,210", "-1250.5" -> "-1,250.5" (other text as it is). */
export function thousands(text) {
  return String(text).replace(/^([-\u2212+]?)(\d{4,})/, (_, sign, digits) => sign + digits.replace(/\B(?=(\d{3})+$)/g, ","));
}
