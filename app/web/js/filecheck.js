// What a road file carries (superelevation, grades, posted speeds), read on the page when the file is chosen, and
// which inputs it still needs -- said before any request, in words, once, beside the box that supplies it. The page
// sends only what the user typed: a file without a superelevation needs one typed (or a maximum superelevation to
// derive it from the design standard, which then needs a posted speed); a file without posted speeds is assessed
// without flags unless one is typed.

import { $, $$, el, grouped } from "./dom.js";
import { value } from "./form.js";

/** The first bytes of a file tell whether it is text: a NUL byte, or bytes that are not UTF-8, say it is not. */
export function isText(bytes) {
  if (bytes.includes(0)) return false;
  try {
    new TextDecoder("utf-8", { fatal: true }).decode(bytes.subarray(0, Math.max(0, bytes.length - 4)));
    return true;
  } catch {
    return false;
  }
}

const FILE_KINDS = { csv: "a CSV table", landxml: "a LandXML alignment", ifc: "an IFC 4.3 alignment", gpx: "a GPX track", geojson: "a GeoJSON route" };

/**
 * What a file carries, by its format: {superelevation, posted, grade} each true or false, and `what` in words.
 * CSV: the header's columns (any of the dialects the service reads: `,` `;` or tab). LandXML: superelevation or
 * cross-section data, design speeds, a vertical profile. IFC: a cant, a vertical layout. GeoJSON: the features' `superelevation_percent` and
 * `posted_speed_kmh` properties, elevations (a third coordinate). GPX: elevations (`<ele>`); it has no field for the
 * others.
 */
export function carries(kind, text) {
  const head = text.slice(0, 200_000);
  if (kind === "csv") {
    const header = head.replace(/^\ufeff/, "").split(/\r?\n/, 1)[0].toLowerCase();
    const columns = header.split(/[,;\t]/).map((c) => c.trim().replace(/^"|"$/g, ""));
    return {
      superelevation: columns.includes("superelevation_percent"),
      posted: columns.includes("posted_speed_kmh"),
      grade: columns.includes("grade_percent"),
    };
  }
  if (kind === "landxml") {
    return {
      superelevation: /<(\w+:)?(Superelevation|SuperelevationRecord|CrossSects|Cant)[\s>/]/.test(text),
      posted: /<(\w+:)?(DesignSpeed|DesignSpeed85th|Speeds)[\s>/]/.test(text),
      grade: /<(\w+:)?(ProfAlign|PVI|ParaCurve|CircCurve)[\s>/]/.test(text),
    };
  }
  if (kind === "ifc") {
    // its cant is read as superelevation, its vertical layout as the profile; the service reads no posted speed
    // from an IFC file (docs/uploads.md "IFC 4.3", what it reads)
    return { superelevation: /IFCALIGNMENTCANT\(/i.test(text), posted: false, grade: /IFCALIGNMENTVERTICAL\(/i.test(text) };
  }
  if (kind === "geojson") {
    return {
      superelevation: /"superelevation_percent"\s*:\s*-?\d/.test(text),
      posted: /"posted_speed_kmh"\s*:\s*\d/.test(text),
      grade: /\[\s*-?[\d.]+\s*,\s*-?[\d.]+\s*,\s*-?[\d.]+\s*\]/.test(head),
    };
  }
  return { superelevation: false, posted: false, grade: /<ele>/.test(head) }; // gpx
}

/** The notes of one file against the boxes: [{box, text, blocks}] (blocks: no request can be made without it). */
export function needs(kind, name, has) {
  const typed = (id) => value($(id)) !== undefined;
  const out = [];
  const e = typed("#al-e");
  const emax = typed("#al-emax");
  const posted = typed("#al-posted");
  if (!has.superelevation && !e && !emax) {
    out.push({
      box: "#al-e",
      blocks: true,
      text: `${name} gives no superelevation: type the superelevation [%] of its curves here, or a maximum superelevation [%] in its box to derive it from the design standard.`,
    });
  } else if (!has.superelevation && !e && !has.posted && !posted) {
    out.push({
      box: "#al-posted",
      blocks: true,
      text: `${name} gives no superelevation and no posted speed: a superelevation derived from the maximum superelevation needs the posted speed [km/h]; type it here, or the superelevation [%] of its curves in its box.`,
    });
  } else if (!has.posted && !posted) {
    out.push({
      box: "#al-posted",
      blocks: false,
      text: `${name} gives no posted speed: its curves get a safe speed but none can be flagged; type the posted speed [km/h] to flag them.`,
    });
  }
  if ((kind === "landxml" || kind === "ifc") && !has.grade && !typed("#al-grade")) {
    out.push({ box: "#al-grade", blocks: false, text: `${name} has no vertical profile: its curves are assessed as level unless a grade [%] is typed here.` });
  }
  return out;
}

/** Replace the notes beside the boxes with `notes` (each box's note tied to it by aria-describedby). */
export function showNotes(notes) {
  for (const old of $$(".file-note")) {
    const box = $(`[aria-describedby~="${old.id}"]`);
    if (box) {
      const rest = box.getAttribute("aria-describedby").split(" ").filter((id) => id !== old.id);
      if (rest.length) box.setAttribute("aria-describedby", rest.join(" "));
      else box.removeAttribute("aria-describedby");
    }
    old.remove();
  }
  for (const [i, note] of notes.entries()) {
    const box = $(note.box);
    const id = `file-note-${i}`;
    box.closest(".field").append(el("p", { id, class: note.blocks ? "file-note needed" : "file-note" }, note.text));
    box.setAttribute("aria-describedby", [box.getAttribute("aria-describedby"), id].filter(Boolean).join(" "));
  }
}

/** One line on what the file is and carries, under the file box. */
export function describe(kind, name, text, has, rows) {
  const parts = [`${name}: ${FILE_KINDS[kind]}`];
  if (typeof rows === "number") parts.push(`${grouped(rows, 0)} ${["csv", "landxml", "ifc"].includes(kind) ? "curves" : "points"}`);
  const listed = [
    has.superelevation ? "superelevations" : null,
    has.posted ? "posted speeds" : null,
    has.grade ? (kind === "gpx" || kind === "geojson" ? "elevations (the grades are read from them)" : "grades") : null,
  ].filter(Boolean);
  parts.push(listed.length ? `with ${listed.join(", ")}` : "with no superelevation, posted speed or grade");
  return `${parts.join(", ")}.`;
}
