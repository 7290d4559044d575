// Results that no longer describe the inputs: the moment an input changes (or a request fails) every result panel
// that depends on it is marked stale -- greyed, with a banner in words tied to it by aria-describedby and
// `data-stale` on the panel -- until the next successful computation redraws it.

import { $, el } from "./dom.js";

/** The result panels, by name: the element that holds the result. */
export const PANELS = {
  srt: "#results-body",
  design: "#road-results",
  speed: "#speed-result",
  advisory: "#advisory-result",
  limits: "#limits-result",
  builder: "#build-result",
  combo: "#cb-result",
  superelevation: "#super-output",
  alignment: "#alignment-results",
  dynamics: "#dyn-results",
  summary: "#summary-body",
};

/** Which panels an input of each part of the page invalidates. */
export const DEPENDS = {
  vehicle: ["srt", "design", "speed", "advisory", "limits", "builder", "combo", "alignment", "dynamics", "summary"],
  case: ["srt", "design", "speed", "advisory", "limits", "alignment", "summary"],
  road: ["design", "summary"],
  speed: ["speed", "advisory", "summary"],
  standard: ["design", "advisory", "superelevation", "alignment", "summary"],
  superelevation: ["superelevation"],
  limits: ["limits"],
  alignment: ["alignment"],
  dynamics: ["dynamics"],
};

export const CHANGED = "Stale \u2014 inputs changed, press Compute";
export const FAILED = "Stale \u2014 the last request failed (see the message at the inputs); this is the previous result";

const hasContent = (node) => node && !node.hidden && node.childNodes.length > 0 && node.textContent.trim() !== "";

/** The sticky bar's headline follows the SRT panel. */
function syncBar() {
  const staleSrt = $(PANELS.srt)?.dataset.stale === "true";
  const bar = $("#bar-stale");
  if (bar) bar.hidden = !staleSrt;
  $("#bar-result")?.classList.toggle("stale", staleSrt);
  document.body.dataset.stale = String(Object.keys(PANELS).filter((n) => $(PANELS[n])?.dataset.stale === "true").length);
}

/** Mark the panels `names` stale with `text` (panels without a result are left alone). */
export function mark(names, text = CHANGED) {
  for (const name of names) {
    const panel = $(PANELS[name]);
    if (!hasContent(panel)) continue;
    const id = `stale-${name}`;
    let banner = document.getElementById(id);
    if (!banner) {
      banner = el("p", { class: "stale-banner", id, role: "status" });
      panel.before(banner);
    }
    banner.textContent = text;
    panel.dataset.stale = "true";
    panel.classList.add("stale");
    const ids = new Set((panel.getAttribute("aria-describedby") || "").split(" ").filter(Boolean));
    ids.add(id);
    panel.setAttribute("aria-describedby", [...ids].join(" "));
  }
  syncBar();
}

/** The panels `names` show a fresh result again. */
export function fresh(names) {
  for (const name of names) {
    const panel = $(PANELS[name]);
    if (!panel) continue;
    document.getElementById(`stale-${name}`)?.remove();
    delete panel.dataset.stale;
    panel.classList.remove("stale");
    const rest = (panel.getAttribute("aria-describedby") || "").split(" ").filter((i) => i && i !== `stale-${name}`);
    if (rest.length) panel.setAttribute("aria-describedby", rest.join(" "));
    else panel.removeAttribute("aria-describedby");
  }
  syncBar();
}

/** Mark stale on every edit inside `root` (typing, choosing, a file): the parts `part` depends on. */
export function watch(root, part) {
  const handler = (ev) => {
    if (ev.target.closest?.("[data-no-stale]")) return;
    mark(DEPENDS[part]);
  };
  root.addEventListener("input", handler);
  root.addEventListener("change", handler);
}
