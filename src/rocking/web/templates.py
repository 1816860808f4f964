"""The web app's pages: Jinja templates kept as strings (no package data, no build step).

Names end in ``.html`` so that Flask autoescapes every value.
"""

from __future__ import annotations

__all__ = ["TEMPLATES"]

_CSS = """
* { box-sizing: border-box; }
html { scroll-padding-bottom: 4em; }  /* a field scrolled into view is not hidden under the Run bar */
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; margin: 0;
       color: #1d2430; background: #f4f5f7; font-size: 15px; }
header { background: #22303f; color: #fff; padding: 0.7em 1.4em; }
header h1 { font-size: 1.25em; margin: 0; font-weight: 600; }
header p { margin: 0.2em 0 0; color: #c9d3de; font-size: 0.9em; }
header a { color: #fff; }
main { display: flex; gap: 1.4em; padding: 1.2em 1.4em; align-items: flex-start; flex-wrap: wrap; }
#inputs { flex: 0 1 390px; min-width: 0; max-width: 100%; background: #fff; border: 1px solid #d9dde3;
          border-radius: 6px; padding: 0.8em 1em; }
#output { flex: 1 1 560px; min-width: 0; max-width: 100%; }
fieldset { border: 1px solid #e1e4e8; border-radius: 5px; margin: 0 0 0.8em; padding: 0.5em 0.8em 0.6em; min-width: 0; }
legend { font-weight: 600; padding: 0 0.3em; }
label { display: flex; justify-content: space-between; align-items: center; gap: 0.6em; margin: 0.3em 0;
        font-size: 0.92em; }
label.check { justify-content: flex-start; flex-wrap: nowrap; }
input[type=text], input[type=number], select { width: 10.5em; padding: 0.22em 0.35em; font-size: 0.95em;
        border: 1px solid #b9c0c8; border-radius: 3px; }
select#record { width: 15.5em; }
input[type=file] { width: 15.5em; font-size: 0.85em; }
.hint { color: #667; font-size: 0.8em; margin: 0.2em 0 0.3em; }
.buttons { display: flex; gap: 0.6em; margin-top: 0.4em; align-items: center; flex-wrap: wrap; }
/* Run, and what it is doing, stay at the bottom of the screen while the form scrolls */
#run-bar { position: sticky; bottom: 0; z-index: 2; background: #fff; margin: 0.4em -0.3em 0; padding: 0.45em 0.3em;
           border-top: 1px solid #e1e4e8; }
button { font-size: 1em; padding: 0.45em 1.1em; border-radius: 4px; border: 1px solid #2f5f8f;
         background: #2f6fab; color: #fff; cursor: pointer; }
button.secondary { background: #fff; color: #2f5f8f; }
button:disabled { opacity: 0.6; cursor: wait; }
.busy { color: #2f5f8f; font-size: 0.9em; }
.busy[hidden] { display: none; }
.busy::before { content: ""; display: inline-block; width: 0.8em; height: 0.8em; margin-right: 0.4em;
                border: 2px solid #9db7d3; border-top-color: #2f5f8f; border-radius: 50%; vertical-align: -0.1em;
                animation: spin 0.9s linear infinite; }
@keyframes spin { to { transform: rotate(360deg); } }
#pga-preview { color: #2f5f8f; }
.card { background: #fff; border: 1px solid #d9dde3; border-radius: 6px; padding: 0.9em 1.1em; margin-bottom: 1.1em; }
.card h2 { font-size: 1.05em; margin: 0 0 0.6em; }
.error { background: #fdecea; border: 1px solid #e0a9a3; color: #7d1d12; border-radius: 6px;
         padding: 0.8em 1em; margin-bottom: 1.1em; white-space: pre-wrap; overflow-wrap: anywhere; }
.verdict { font-size: 1.12em; font-weight: 600; padding: 0.7em 0.9em; border-radius: 5px; margin: 0 0 0.8em; }
.verdict.safe { background: #e7f4ea; border-left: 6px solid #2e8b45; }
.verdict.fails { background: #fdecea; border-left: 6px solid #c0392b; }
.verdict.stopped { background: #fff4e0; border-left: 6px solid #d68910; }
table { border-collapse: collapse; font-size: 0.92em; max-width: 100%; }
td, th { padding: 0.22em 0.8em 0.22em 0; text-align: left; vertical-align: top; overflow-wrap: anywhere; }
th { font-weight: 600; border-bottom: 1px solid #ccd; }
td.name { color: #445; }
.tables { display: flex; gap: 2.2em; flex-wrap: wrap; align-items: flex-start; }
fieldset.off label:not(.check) { opacity: 0.45; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.figures figure { margin: 0; }
.figures figure { max-width: 100%; }
.figures img { max-width: 100%; height: auto; border: 1px solid #e1e4e8; background: #fff; }
figcaption { font-size: 0.82em; color: #556; margin-top: 0.2em; max-width: 640px; }
ul.warnings li, li.warning { color: #8a4b00; }
#sweep-verdict-lines li { overflow-wrap: anywhere; }  /* a record's name has no space to break at */
progress { width: 100%; height: 1.3em; }
.muted { color: #667; font-size: 0.85em; }
a.download { display: inline-block; margin: 0.3em 0.8em 0.3em 0; }
tr.best td { font-weight: 600; background: #e7f4ea; }
.scroll { max-width: 100%; overflow-x: auto; }  /* a wide table scrolls inside its card on a phone */
#sweep-table td, #sweep-table th { overflow-wrap: normal; white-space: nowrap; }
/* the stack of blocks: a block per small fieldset, its fields two by two, labels above them */
.modes label.check { margin: 0.25em 0; }
fieldset.block { margin: 0.5em 0 0.6em; padding: 0.3em 0.6em 0.5em; }
fieldset.block legend { display: flex; gap: 0.5em; align-items: baseline; font-weight: 600; }
fieldset.block legend .on { font-weight: normal; color: #667; font-size: 0.85em; }
fieldset.block .grid { display: grid; grid-template-columns: repeat(2, minmax(0, 1fr)); gap: 0 0.8em; }
fieldset.block label { display: block; margin: 0.2em 0; font-size: 0.85em; }
fieldset.block input[type=text] { display: block; width: 100%; margin-top: 0.1em; }
fieldset.block .interface { grid-column: 1 / -1; margin: 0.35em 0 0; font-size: 0.8em; color: #556; }
button.small { font-size: 0.8em; padding: 0.1em 0.6em; }
[hidden] { display: none !important; }
#verdict.stack::first-letter { text-transform: uppercase; }
.data th { vertical-align: bottom; overflow-wrap: normal; }  /* headers wrap, so a phone shows every column */
.data td { overflow-wrap: normal; }  /* a name breaks at a space or a dash, not inside a word */
.data td.num { white-space: nowrap; }
.data td.num, .data th.num { text-align: right; }
/* a phone: one column, labels above their fields where both do not fit on one line */
@media (max-width: 640px) {
  body { font-size: 16px; }
  header { padding: 0.6em 0.8em; }
  header h1 { font-size: 1.1em; }
  main { padding: 0.7em 0.5em; gap: 0.9em; }
  #inputs { flex: 1 1 100%; padding: 0.6em 0.6em; }
  #output { flex: 1 1 100%; }
  fieldset { padding: 0.4em 0.6em 0.5em; }
  label { flex-wrap: wrap; }
  input[type=text], input[type=number], select { width: 9.5em; font-size: 16px; }
  select#record, input[type=file] { width: 100%; }
  .card { padding: 0.7em 0.7em; }
  .tables { gap: 1em; }
  .tables table { width: 100%; }
  .tables .scroll table { width: auto; }
  fieldset.block input[type=text] { width: 100%; }
  .data { font-size: 0.8em; }
  .data th, .data td { padding-right: 0.45em; }
  .figures figure, .figures img { width: 100%; }
  td.name { width: 48%; }
}
"""

_BASE = (
    """<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{% block title %}rocking{% endblock %}</title>
<style>"""
    + _CSS
    + """</style>
{% block head %}{% endblock %}
</head>
<body>
<header>
  <h1><a href="{{ url_for('index') }}" style="text-decoration:none">rocking</a> — statue on a pedestal under a recorded floor motion</h1>
  <p>Choose or upload an accelerogram, scale it, describe the statue and its pedestal (or a stack of blocks), and run.
     Rigid-block model; SI units. Version {{ version }}.</p>
</header>
<main>
{% block main %}{% endblock %}
</main>
</body>
</html>
"""
)

_FORM = """
<form id="inputs" method="post" action="{{ url_for('run') }}" enctype="multipart/form-data">
  <fieldset class="modes">
    <legend>What stands on the floor</legend>
    {% for value, text in modes %}
    <label class="check"><input id="mode-{{ value }}" name="mode" type="radio" value="{{ value }}"{% if value == form.mode or (form.mode not in ['statue', 'stack'] and value == 'statue') %} checked{% endif %}> {{ text }}</label>
    {% endfor %}
  </fieldset>
  <fieldset>
    <legend>Floor motion</legend>
    <label>bundled record
      <select id="record" name="record">
      {% for r in records %}
        <option value="{{ r.name }}" data-pga-g="{{ r.pga_g if r.pga_g is not none else '' }}"{% if r.name == form.record %} selected{% endif %}>{{ r.label }}</option>
      {% endfor %}
      </select>
    </label>
    <label>or upload a file <input id="upload" type="file" name="upload" data-max-bytes="{{ max_upload_bytes }}"></label>
    <p class="hint">PEER AT2, ESM ASCII or two-column text (time, acceleration), at most {{ max_upload }};
       an uploaded file replaces the bundled record.</p>
    <label>file format
      <select id="format" name="format">
      {% for value, text in formats %}
        <option value="{{ value }}"{% if value == form.format %} selected{% endif %}>{{ text }}</option>
      {% endfor %}
      </select>
    </label>
    <label>units of the file
      <select id="units" name="units">
      {% for value, text in units %}
        <option value="{{ value }}"{% if value == form.units %} selected{% endif %}>{{ text }}</option>
      {% endfor %}
      </select>
    </label>
    <label>scale by
      <select id="scale_kind" name="scale_kind">
      {% for value, text in scale_kinds %}
        <option value="{{ value }}"{% if value == form.scale_kind %} selected{% endif %}>{{ text }}</option>
      {% endfor %}
      </select>
    </label>
    <label>value <input id="scale_value" name="scale_value" type="text" inputmode="decimal" value="{{ form.scale_value }}"></label>
    <p class="hint" id="pga-preview" aria-live="polite"></p>
    <label>duration (s) <input id="duration" name="duration" type="text" inputmode="decimal" value="{{ form.duration }}" placeholder="the record's length" title="at most {{ max_duration }} s on this server"></label>
  </fieldset>
  <fieldset id="statue-fields"{% if form.mode == 'stack' %} hidden{% endif %}>
    <legend>Statue</legend>
    <label>width B (m) <input id="statue_width" name="statue_width" type="text" inputmode="decimal" value="{{ form.statue_width }}"></label>
    <label>height H (m) <input id="statue_height" name="statue_height" type="text" inputmode="decimal" value="{{ form.statue_height }}"></label>
    <label>mass (kg) <input id="statue_mass" name="statue_mass" type="text" inputmode="decimal" value="{{ form.statue_mass }}"></label>
    <label>restitution r <input id="statue_restitution" name="statue_restitution" type="text" inputmode="decimal" value="{{ form.statue_restitution }}" placeholder="Housner's value"></label>
    <label>friction μs <input id="statue_mu_s" name="statue_mu_s" type="text" inputmode="decimal" value="{{ form.statue_mu_s }}" placeholder="never slides"></label>
    <label>friction μk <input id="statue_mu_k" name="statue_mu_k" type="text" inputmode="decimal" value="{{ form.statue_mu_k }}" placeholder="= μs"></label>
    <p class="hint">Friction under the statue: on the floor without a pedestal, on the pedestal's top (checked only) with one.</p>
  </fieldset>
  <fieldset id="pedestal-fields"{% if form.mode == 'stack' %} hidden{% endif %}>
    <legend>Pedestal</legend>
    <label class="check"><input id="pedestal" name="pedestal" type="checkbox" value="on"{% if form.pedestal %} checked{% endif %}> the statue stands on a pedestal that can slide</label>
    <label>mass (kg) <input id="pedestal_mass" name="pedestal_mass" type="text" inputmode="decimal" value="{{ form.pedestal_mass }}"></label>
    <label>floor friction μs <input id="pedestal_mu_s" name="pedestal_mu_s" type="text" inputmode="decimal" value="{{ form.pedestal_mu_s }}"></label>
    <label>floor friction μk <input id="pedestal_mu_k" name="pedestal_mu_k" type="text" inputmode="decimal" value="{{ form.pedestal_mu_k }}" placeholder="= μs"></label>
    <label>width (m) <input id="pedestal_width" name="pedestal_width" type="text" inputmode="decimal" value="{{ form.pedestal_width }}" placeholder="optional"></label>
    <label>height (m) <input id="pedestal_height" name="pedestal_height" type="text" inputmode="decimal" value="{{ form.pedestal_height }}" placeholder="optional"></label>
  </fieldset>
  <fieldset id="stack-fields"{% if form.mode != 'stack' %} hidden{% endif %}>
    <legend>Stack of blocks, from the floor up</legend>
    <input id="stack_blocks" name="stack_blocks" type="hidden" value="{{ shown_blocks }}">
    <p class="hint">Block 1 stands on the floor, each next block on the one below; every contact may stick, slip,
      rock and lift off. Offset: the block's centre to the right of the centre of the block below (m). μs left
      empty: that contact never slips; r left empty: Housner's rule.</p>
    {% for k in range(1, max_blocks + 1) %}
    {% set p = "block" ~ k %}
    <fieldset class="block" id="{{ p }}"{% if k > shown_blocks %} hidden{% endif %}>
      <legend>Block {{ k }} <span class="on">on {{ "the floor" if k == 1 else "block " ~ (k - 1) }}</span>
        <button type="button" class="secondary small remove" data-block="{{ k }}" title="remove block {{ k }}">remove</button></legend>
      <div class="grid">
        <label>name <input id="{{ p }}_name" name="{{ p }}_name" type="text" value="{{ form[p ~ '_name'] }}" placeholder="block {{ k }}" maxlength="40"></label>
        <label>offset (m) <input id="{{ p }}_offset" name="{{ p }}_offset" type="text" inputmode="decimal" value="{{ form[p ~ '_offset'] }}" placeholder="0, centred"></label>
        <label>width B (m) <input id="{{ p }}_width" name="{{ p }}_width" type="text" inputmode="decimal" value="{{ form[p ~ '_width'] }}"></label>
        <label>height H (m) <input id="{{ p }}_height" name="{{ p }}_height" type="text" inputmode="decimal" value="{{ form[p ~ '_height'] }}"></label>
        <label>mass (kg) <input id="{{ p }}_mass" name="{{ p }}_mass" type="text" inputmode="decimal" value="{{ form[p ~ '_mass'] }}"></label>
        <p class="interface">The contact under it, on {{ "the floor" if k == 1 else "block " ~ (k - 1) }}:</p>
        <label>friction μs <input id="{{ p }}_mu_s" name="{{ p }}_mu_s" type="text" inputmode="decimal" value="{{ form[p ~ '_mu_s'] }}" placeholder="never slips"></label>
        <label>friction μk <input id="{{ p }}_mu_k" name="{{ p }}_mu_k" type="text" inputmode="decimal" value="{{ form[p ~ '_mu_k'] }}" placeholder="= μs"></label>
        <label>restitution r <input id="{{ p }}_restitution" name="{{ p }}_restitution" type="text" inputmode="decimal" value="{{ form[p ~ '_restitution'] }}" placeholder="Housner's rule"></label>
      </div>
    </fieldset>
    {% endfor %}
    <div class="buttons"><button id="add-block" class="secondary" type="button">Add a block on top</button>
      <span id="block-count" class="muted" data-max="{{ max_blocks }}">{{ shown_blocks }} of at most {{ max_blocks }} blocks</span></div>
  </fieldset>
  <div class="buttons" id="run-bar"><button id="run" type="submit">Run</button>
    <span id="busy" class="busy" role="status" hidden data-limit="{{ timeout }}">Running… (at most {{ timeout }} s)</span></div>
  <fieldset id="sweep-fields" style="margin-top:1em"{% if form.mode == 'stack' %} hidden{% endif %}>
    <legend>Friction design sweep</legend>
    <p class="hint">Runs the statue on its pedestal for several floor frictions μs of the pedestal
      (μk/μs as entered above) and writes a report for the best value.</p>
    <label>μs from <input id="sweep_from" name="sweep_from" type="text" inputmode="decimal" value="{{ form.sweep_from }}"></label>
    <label>μs to <input id="sweep_to" name="sweep_to" type="text" inputmode="decimal" value="{{ form.sweep_to }}"></label>
    <label>values (2–{{ max_sweep_points }}) <input id="sweep_points" name="sweep_points" type="text" inputmode="numeric" value="{{ form.sweep_points }}"></label>
    <label>sliding limit (mm) <input id="sweep_sliding_limit" name="sweep_sliding_limit" type="text" inputmode="decimal" value="{{ form.sweep_sliding_limit }}" placeholder="none"></label>
    <p class="hint">The free space around the pedestal: values that let it slide farther are not recommended.</p>
    <label>friction scatter s <input id="sweep_scatter" name="sweep_scatter" type="text" inputmode="decimal" value="{{ form.sweep_scatter }}" placeholder="0.2"></label>
    <p class="hint">Measured friction varies with the surfaces, humidity and age: a value counts as safe only if the
      statue stands at μs·(1 − s), μs and μs·(1 + s), μk alike (0 checks μs alone).</p>
    <div class="buttons"><button id="sweep" class="secondary" type="submit" formaction="{{ url_for('start_sweep') }}">Run design sweep</button>
      <span id="sweep-busy" class="busy" role="status" hidden>Starting the design sweep…</span></div>
  </fieldset>
</form>
<script>
(function () {
  var form = document.getElementById("inputs");
  var box = document.getElementById("pedestal");
  function sync() {  // dimmed, not disabled: the values stay in the form for the next run
    document.getElementById("pedestal-fields").classList.toggle("off", !box.checked);
  }
  box.addEventListener("change", sync);
  sync();

  // statue or stack: only the fields of the chosen mode show (the others keep their values)
  var modes = document.querySelectorAll("input[name=mode]");
  function showMode() {
    var stack = document.getElementById("mode-stack").checked;
    ["statue-fields", "pedestal-fields", "sweep-fields"].forEach(function (id) {
      document.getElementById(id).hidden = stack;
    });
    document.getElementById("stack-fields").hidden = !stack;
  }
  modes.forEach(function (el) { el.addEventListener("change", showMode); });
  showMode();

  // the blocks: add one on top, or remove any (those above move down one place)
  var count = document.getElementById("stack_blocks");
  var countText = document.getElementById("block-count");
  var MAX_BLOCKS = Number(countText.getAttribute("data-max"));
  var FIELDS = ["name", "offset", "width", "height", "mass", "mu_s", "mu_k", "restitution"];
  function field(k, f) { return document.getElementById("block" + k + "_" + f); }
  function showBlocks() {
    var n = Number(count.value);
    for (var k = 1; k <= MAX_BLOCKS; k++) { document.getElementById("block" + k).hidden = k > n; }
    document.querySelectorAll("#stack-fields button.remove").forEach(function (b) { b.disabled = n <= 1; });
    document.getElementById("add-block").disabled = n >= MAX_BLOCKS;
    countText.textContent = n + " of at most " + MAX_BLOCKS + " blocks";
  }
  document.getElementById("add-block").addEventListener("click", function () {
    var n = Math.min(Number(count.value) + 1, MAX_BLOCKS);
    count.value = n;
    showBlocks();
    field(n, "width").focus();
  });
  document.querySelectorAll("#stack-fields button.remove").forEach(function (b) {
    b.addEventListener("click", function () {
      var n = Number(count.value), k = Number(b.getAttribute("data-block"));
      if (n <= 1) { return; }
      for (var j = k; j < n; j++) {
        FIELDS.forEach(function (f) { field(j, f).value = field(j + 1, f).value; });
      }
      FIELDS.forEach(function (f) { field(n, f).value = ""; });
      count.value = n - 1;
      showBlocks();
    });
  });
  showBlocks();

  // the PGA the scale gives, before running (the same arithmetic as the server: g = 9.80665 m/s²)
  var G = 9.80665;
  var record = document.getElementById("record"), upload = document.getElementById("upload");
  var kind = document.getElementById("scale_kind"), value = document.getElementById("scale_value");
  var preview = document.getElementById("pga-preview");
  function number(text) {
    text = text.trim();
    if (text.split(",").length === 2 && text.indexOf(".") < 0) { text = text.replace(",", "."); }
    var x = Number(text);
    return text !== "" && isFinite(x) ? x : null;
  }
  function fmt(x, digits) { return x.toFixed(digits); }
  function showPga() {
    var v = number(value.value), k = kind.value;
    var file = upload.files && upload.files.length ? upload.files[0].name : null;
    var opt = record.options[record.selectedIndex];
    var pga = opt && opt.getAttribute("data-pga-g") ? Number(opt.getAttribute("data-pga-g")) : null;
    var text = "";
    if (value.value.trim() === "") {
      text = file ? "PGA: that of " + file : (pga ? "PGA: the record's " + fmt(pga, 3) + " g" : "");
    } else if (v === null || !(v > 0)) {
      text = "enter a positive number";
    } else if (k === "factor") {
      text = file ? "PGA after scaling: " + v + " × that of " + file + " (shown after the run)"
           : (pga ? "PGA after scaling: " + fmt(v * pga, 3) + " g = " + fmt(v * pga * G, 2) + " m/s² (the record's "
                    + fmt(pga, 3) + " g × " + v + ")" : "");
    } else {
      var g = k === "pga_g" ? v : v / G;
      text = "PGA after scaling: " + fmt(g, 3) + " g = " + fmt(g * G, 2) + " m/s²"
           + (!file && pga ? " (the record × " + fmt(g / pga, 3) + ")" : "");
    }
    preview.textContent = text;
  }
  [record, upload, kind].forEach(function (el) { el.addEventListener("change", showPga); });
  value.addEventListener("input", showPga);
  showPga();

  // Run and the sweep post the form in the background: the page, and the file chosen, stay as
  // they are; the answer replaces the output, which is brought into view (below the form on a phone)
  var timer = null;
  function busy(on, which) {
    document.querySelectorAll("#inputs button").forEach(function (b) { b.disabled = on; });
    if (!on) { showBlocks(); }
    var el = document.getElementById(which);
    if (timer) { clearInterval(timer); timer = null; }
    document.querySelectorAll("#inputs .busy").forEach(function (b) { b.hidden = true; });
    if (!on) { return; }
    el.hidden = false;
    var limit = el.getAttribute("data-limit"), t0 = Date.now();
    if (limit) {
      var tick = function () {
        var s = Math.floor((Date.now() - t0) / 1000);
        el.textContent = "Running… " + s + " s of at most " + limit + " s";
      };
      tick();
      timer = setInterval(tick, 1000);
    }
  }
  function inView(el) {
    var r = el.getBoundingClientRect();
    return r.top >= 0 && r.top < window.innerHeight - 40;
  }
  function show(html) {
    var doc = new DOMParser().parseFromString(html, "text/html");
    var fresh = doc.getElementById("output");
    if (!fresh) { throw new Error("the answer holds no result"); }
    document.getElementById("output").replaceWith(document.adoptNode(fresh));
    document.title = doc.title;
    var target = document.getElementById("verdict") || document.getElementById("error");
    if (target && !inView(target)) { target.scrollIntoView({block: "start"}); }
  }
  function failed(message) {
    var out = document.getElementById("output");
    out.innerHTML = "";
    var div = document.createElement("div");
    div.id = "error"; div.className = "error"; div.setAttribute("role", "alert");
    div.textContent = "The server did not answer: " + message;
    out.appendChild(div);
    if (!inView(div)) { div.scrollIntoView({block: "start"}); }
  }
  form.addEventListener("submit", function (ev) {
    var big = upload.files && upload.files.length && upload.files[0].size > Number(upload.getAttribute("data-max-bytes"));
    if (!window.fetch || !window.DOMParser || big) {
      // a plain post (the server answers an oversized upload before reading it, which fetch reports as a
      // network error); disabled buttons are not submitted, so wait until the browser has read them
      setTimeout(function () { busy(true, "busy"); }, 0);
      return;
    }
    ev.preventDefault();
    var sweep = ev.submitter && ev.submitter.id === "sweep";
    var action = sweep ? ev.submitter.getAttribute("formaction") : form.getAttribute("action");
    var data = new FormData(form);
    busy(true, sweep ? "sweep-busy" : "busy");
    fetch(action, {method: "POST", body: data, credentials: "same-origin"}).then(function (r) {
      if (r.redirected) { window.location.assign(r.url); return null; }  // a sweep's progress page
      return r.text().then(function (html) { busy(false); show(html); });
    }).catch(function (err) { busy(false); failed(String(err && err.message || err)); });
  });
})();
</script>
"""

_INDEX = (
    """{% extends "base.html" %}
{% block title %}{% if result %}{{ result.verdict }} — {% endif %}rocking{% endblock %}
{% block main %}
"""
    + _FORM
    + """
<section id="output">
{% if error %}
  <div id="error" class="error" role="alert"><strong>{{ error_title or "Cannot run" }}:</strong> {{ error }}</div>
{% endif %}
{% if result %}
  {% include "result.html" %}
{% elif not error %}
  <div class="card">
    <h2>How it works</h2>
    <p>The statue is a rigid block B × H that can rock on its base corners; without a pedestal it may also slide on
    the floor (give its friction), and with one the pedestal slides on the floor and the statue rocks on it.
    <em>Run</em> simulates the chosen record and shows whether the statue overturns, how far it rocks and slides, an
    animation and the response plots. <em>Run design sweep</em> tries a range of floor frictions for the pedestal
    and writes a report (HTML, PDF and CSV) you can download.</p>
    <p>Or choose <em>a stack of blocks</em>: up to {{ max_blocks }} blocks from the floor up (a plinth, a statue, a
    vase…), each free to rock, slide and lift off on the one below, with its own friction and restitution. <em>Run</em>
    then names the block that falls, gives a row per block and per contact, and draws every block.</p>
    <p class="muted">The bundled records are real accelerograms (PEER NGA and ESM); see <code>rocking records</code>.</p>
  </div>
{% endif %}
</section>
{% endblock %}
"""
)

# The summary and motion tables of a result, statue or stack.
_SUMMARY_TABLES = """
  <div class="tables">
    <table id="summary">
      <tr><th colspan="2">Summary</th></tr>
      {% for key, label, text, value in result.rows %}
      <tr><td class="name">{{ label }}</td><td id="{{ key }}" data-value="{{ value }}">{{ text }}</td></tr>
      {% endfor %}
    </table>
    <table id="motion">
      <tr><th colspan="2">Motion</th></tr>
      {% for label, text in result.motion %}
      <tr><td class="name">{{ label }}</td><td>{{ text }}</td></tr>
      {% endfor %}
      <tr><td class="name">computing time</td><td>{{ "%.2f"|format(result.seconds) }} s</td></tr>
      <tr><td class="name">permalink</td><td><a id="permalink" href="{{ url_for('show_run', run_id=result.id) }}">run {{ result.id[:8] }}</a>
        · <a href="{{ url_for('run_file', run_id=result.id, name='result.json') }}">result.json</a></td></tr>
    </table>
  </div>
"""

# The animation and the two plots of a result, statue or stack: the including template sets
# animation_alt, animation_caption (after "Played in real time; ") and figures (key, element id, alt, caption).
_RESULT_FIGURES = """<div class="card">
  <h2>Animation and plots</h2>
  <div class="figures">
    <figure>
      <img id="animation" alt="{{ animation_alt }}" src="{{ url_for('run_file', run_id=result.id, name=result.files.animation) }}">
      <figcaption>{% if result.animation_speed > 1.001 %}Played at {{ "%g"|format(result.animation_speed|round(2)) }}× real
        time (the run is longer than a minute){% else %}Played in real time{% endif %}; {{ animation_caption }}</figcaption>
    </figure>
    {% for key, element, alt, caption in figures %}
    <figure>
      <a href="{{ url_for('run_file', run_id=result.id, name=result.files[key]) }}" title="full size">
      <picture>
        {% if result.files.get(key ~ "_narrow") %}<source media="(max-width: 640px)" srcset="{{ url_for('run_file', run_id=result.id, name=result.files[key ~ '_narrow']) }}">{% endif %}
        <img id="{{ element }}" alt="{{ alt }}" src="{{ url_for('run_file', run_id=result.id, name=result.files[key]) }}">
      </picture></a>
      <figcaption>{{ caption }}</figcaption>
    </figure>
    {% endfor %}
  </div>
</div>
"""

_STACK_RESULT = """
<div class="card" id="result">
  <p id="verdict" class="verdict stack {{ result.verdict_class }}">{{ result.verdict }}</p>
  {% include "summary_tables.html" %}
  <h2 style="margin-top:0.9em">Blocks, from the floor up</h2>
  <div class="scroll"><table id="blocks" class="data">
    <tr><th>block</th><th>overturned</th><th class="num">peak rotation (°)</th><th class="num">peak sliding (mm)</th><th class="num">residual sliding (mm)</th></tr>
    {% for b in result.block_rows %}
    <tr data-values="{{ b["values"] }}"><td>{{ b.name }}</td><td>{{ b.overturned }}</td><td class="num">{{ b.peak_rotation }}</td><td class="num">{{ b.peak_sliding }}</td><td class="num">{{ b.residual_sliding }}</td></tr>
    {% endfor %}
  </table></div>
  <p class="muted">Rotation and sliding of each block on what it stands on (the block below, or the floor).</p>
  <h2>Interfaces, from the floor up</h2>
  <div class="scroll"><table id="interfaces" class="data">
    <tr><th>interface</th><th class="num">friction needed</th><th class="num">μs given</th><th class="num">slip path (mm)</th><th class="num">impacts</th></tr>
    {% for f in result.interface_rows %}
    <tr data-values="{{ f["values"] }}"><td>{{ f.name }}</td><td class="num">{{ f.required_friction }}</td><td class="num">{{ f.given }}</td><td class="num">{{ f.slip_path }}</td><td class="num">{{ f.impacts }}</td></tr>
    {% endfor %}
  </table></div>
  <p class="muted">Friction needed: the largest ratio of tangential to normal force while the contact stuck; a contact
    with μs slips when it needs more, and that slip is simulated.</p>
</div>
{% set animation_alt = "animation of the stack of blocks" %}
{% set animation_caption = "every block drawn to scale where the model puts it, the floor still (the picture moves "
   ~ "with it). The header gives each block's rotation on what it stands on." %}
{% set figures = [
    ("response", "response-plot", "rotation and sliding of every block and the floor acceleration against time",
     "Rotation φ of each block on what it stands on (°), its sliding along that face (mm) and the floor acceleration "
     ~ "against time; one colour per block; a dashed line where a block overturns."),
    ("energy", "energy-plot", "mechanical energy of the stack against time",
     "Change of the stack's mechanical energy E − E₀ since the start (zero: the stack as it started, at rest), with "
     ~ "the ledger W − D (the floor's work less friction and impact losses) dashed over it: the two coincide when "
     ~ "the energy balance closes.")] %}
{% include "result_figures.html" %}
"""

_RESULT = """{% if result.kind == "stack" %}{% include "stack_result.html" %}{% else %}
<div class="card" id="result">
  <p id="verdict" class="verdict {{ result.verdict_class }}">{{ result.verdict }}</p>
  {% include "summary_tables.html" %}
  {% if result.summary.warnings %}
  <ul class="warnings" id="warnings">{% for w in result.summary.warnings %}<li>{{ w }}</li>{% endfor %}</ul>
  {% endif %}
</div>
{% set animation_alt = "animation of the statue" %}
{% set animation_caption = "the colour of the label tells the regime (rest, rock, slide, slide-rock). The floor's "
   ~ "ruler moves with the floor; the trace at the top magnifies the sliding u (mm)." %}
{% set figures = [
    ("response", "response-plot", "rotation, sliding and floor acceleration against time",
     "Rotation θ/α, sliding u and floor acceleration against time; the background shows the regime, ticks mark impacts."),
    ("energy", "energy-plot", "mechanical energy against time",
     "Mechanical energy T + V relative to the floor, with the energy ledger. Zero is the statue standing upright with "
     ~ "everything at rest on the floor; the energy goes below zero only when the statue leans more than 2α "
     ~ "(its centre of mass is then lower than when it stands), that is when it falls.")] %}
{% include "result_figures.html" %}
{% endif %}
"""

_RUN_PAGE = """{% extends "base.html" %}
{% block title %}{{ result.verdict }} — rocking{% endblock %}
{% block main %}
<section id="output">
{% include "result.html" %}
<p><a href="{{ url_for('index') }}">New run</a></p>
</section>
{% endblock %}
"""

_SWEEP = """{% extends "base.html" %}
{% block title %}Friction design sweep — rocking{% endblock %}
{% block head %}
{% if not finished %}<noscript><meta http-equiv="refresh" content="2"></noscript>{% endif %}
{% endblock %}
{% block main %}
<section id="output">
  <div class="card" id="sweep-card" data-state="{{ job.state }}">
    <h2>Friction design sweep of the pedestal's floor friction</h2>
    {% if not finished %}
      <progress id="sweep-progress" max="{{ job.total or 1 }}" value="{{ job.done }}"></progress>
      <p id="sweep-status">{{ job.label or "starting" }}</p>
      <p class="muted">Stopped after {{ job.timeout|round|int }} s at most. This page updates by itself.</p>
      <script>
      (function () {
        var url = {{ url_for('sweep_status', job_id=job.id)|tojson }};
        var bar = document.getElementById("sweep-progress");
        var text = document.getElementById("sweep-status");
        function poll() {
          fetch(url, {cache: "no-store"}).then(function (r) { return r.json(); }).then(function (s) {
            if (s.total) { bar.max = s.total; bar.value = s.done; }
            text.textContent = s.label || s.state;
            if (s.state === "running" || s.state === "queued") { setTimeout(poll, 400); }
            else { window.location.reload(); }
          }).catch(function () { setTimeout(poll, 1500); });
        }
        setTimeout(poll, 300);
      })();
      </script>
    {% elif job.error %}
      <div id="error" class="error" role="alert"><strong>The design sweep failed:</strong> {{ job.error }}</div>
    {% else %}
      {% set r = job.result %}
      <p id="verdict" class="verdict {{ 'safe' if r.meets_limits else ('stopped' if r.recommended else 'fails') }}">{{ r.design_verdict }}</p>
      {% if r.design_lines %}
      <ul id="sweep-verdict-lines">
        {% for line in r.design_lines %}<li{% if line.startswith('Warning') %} class="warning"{% endif %}>{{ line }}</li>{% endfor %}
      </ul>
      {% endif %}
      <p id="sweep-run-verdict">The report's run, at μs = {{ "%.4g"|format(r.best.static_friction) }}
        (μk = {{ "%.4g"|format(r.best.kinetic_friction) }}): {{ r.verdict }}</p>
      <p class="muted" id="sweep-rule">Ranking: {{ r.rule }}. {{ r.rows|length }} values of μs{% if r.friction_scatter %},
        each also at μs·(1 ± {{ "%g"|format(r.friction_scatter) }}){% endif %}; {{ "%.2f"|format(r.duration) }} s
        simulated in the report's run ({{ r.method }}).</p>
      <p id="downloads">
        <a class="download" id="download-report" href="{{ url_for('sweep_file', job_id=job.id, name='report.html') }}">report (HTML)</a>
        {% if 'report.pdf' in r.files %}<a class="download" id="download-pdf" href="{{ url_for('sweep_file', job_id=job.id, name='report.pdf') }}" download>report (PDF)</a>{% endif %}
        <a class="download" id="download-csv" href="{{ url_for('sweep_file', job_id=job.id, name='sweep.csv') }}" download>sweep.csv</a>
        <a class="download" id="download-zip" href="{{ url_for('sweep_file', job_id=job.id, name='sweep-report.zip') }}" download>everything (zip)</a>
      </p>
      <div class="figures">
        <figure><img id="sweep-plot" alt="peak rotation and sliding against the pedestal's friction" src="{{ url_for('sweep_file', job_id=job.id, name='sweep.png') }}"></figure>
        <div class="scroll"><table id="sweep-table">
          <tr><th>μs</th><th>μk</th><th>overturns at μs</th><th>peak θ/α</th><th>peak sliding</th><th>impacts</th>
            <th>within μs·(1 ± s)</th><th>free space needed</th><th>limits</th></tr>
          {% for row in r.rows %}
          <tr{% if row.static_friction == r.best.static_friction %} class="best"{% endif %}>
            <td>{{ "%.4g"|format(row.static_friction) }}{% if row.inverted %} ⚠{% endif %}</td><td>{{ "%.4g"|format(row.kinetic_friction) }}</td>
            <td>{% if row.overturned %}at {{ "%.2f"|format(row.overturn_time) }} s{% else %}no{% endif %}</td>
            <td>{{ "%.3f"|format(row.peak_rotation_over_alpha) }}</td>
            <td>{{ "%.1f"|format(1000 * row.peak_sliding) }} mm</td><td>{{ row.impacts }}</td>
            <td>{% if row.safe %}safe{% elif row.falls %}falls{% else %}undetermined{% endif %}</td>
            <td>{{ "%.1f"|format(1000 * row.clearance) }} mm</td><td>{% if row.meets_limits %}met{% else %}missed{% endif %}</td>
          </tr>
          {% endfor %}
        </table></div>
      </div>
    {% endif %}
  </div>
  <p><a id="back" href="{{ url_for('sweep_inputs', job_id=job.id) }}">Back to the inputs</a> ·
     <a href="{{ url_for('index') }}">New run</a></p>
</section>
{% endblock %}
"""

TEMPLATES = {
    "base.html": _BASE,
    "index.html": _INDEX,
    "result.html": _RESULT,
    "stack_result.html": _STACK_RESULT,
    "summary_tables.html": _SUMMARY_TABLES,
    "result_figures.html": _RESULT_FIGURES,
    "run.html": _RUN_PAGE,
    "sweep.html": _SWEEP,
}
