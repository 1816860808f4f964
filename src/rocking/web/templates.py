"""The web app's pages: Jinja templates kept as strings (no package data, no build step).

Names end in ``.html`` so that Flask autoescapes every value.
"""

from __future__ import annotations

__all__ = ["TEMPLATES"]

_CSS = """
* { box-sizing: border-box; }
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; margin: 0;
       color: #1d2430; background: #f4f5f7; font-size: 15px; }
header { background: #22303f; color: #fff; padding: 0.7em 1.4em; }
header h1 { font-size: 1.25em; margin: 0; font-weight: 600; }
header p { margin: 0.2em 0 0; color: #c9d3de; font-size: 0.9em; }
header a { color: #fff; }
main { display: flex; gap: 1.4em; padding: 1.2em 1.4em; align-items: flex-start; flex-wrap: wrap; }
#inputs { flex: 0 0 390px; background: #fff; border: 1px solid #d9dde3; border-radius: 6px; padding: 0.8em 1em; }
#output { flex: 1 1 560px; min-width: 0; }
fieldset { border: 1px solid #e1e4e8; border-radius: 5px; margin: 0 0 0.8em; padding: 0.5em 0.8em 0.6em; }
legend { font-weight: 600; padding: 0 0.3em; }
label { display: flex; justify-content: space-between; align-items: center; gap: 0.6em; margin: 0.3em 0;
        font-size: 0.92em; }
label.check { justify-content: flex-start; }
input[type=text], input[type=number], select { width: 10.5em; padding: 0.22em 0.35em; font-size: 0.95em;
        border: 1px solid #b9c0c8; border-radius: 3px; }
select#record { width: 15.5em; }
input[type=file] { width: 15.5em; font-size: 0.85em; }
.hint { color: #667; font-size: 0.8em; margin: 0.2em 0 0.3em; }
.buttons { display: flex; gap: 0.6em; margin-top: 0.4em; }
button { font-size: 1em; padding: 0.45em 1.1em; border-radius: 4px; border: 1px solid #2f5f8f;
         background: #2f6fab; color: #fff; cursor: pointer; }
button.secondary { background: #fff; color: #2f5f8f; }
button:disabled { opacity: 0.6; cursor: wait; }
#busy { display: none; color: #2f5f8f; margin-top: 0.5em; font-size: 0.9em; }
.card { background: #fff; border: 1px solid #d9dde3; border-radius: 6px; padding: 0.9em 1.1em; margin-bottom: 1.1em; }
.card h2 { font-size: 1.05em; margin: 0 0 0.6em; }
.error { background: #fdecea; border: 1px solid #e0a9a3; color: #7d1d12; border-radius: 6px;
         padding: 0.8em 1em; margin-bottom: 1.1em; white-space: pre-wrap; overflow-wrap: anywhere; }
.verdict { font-size: 1.12em; font-weight: 600; padding: 0.7em 0.9em; border-radius: 5px; margin: 0 0 0.8em; }
.verdict.safe { background: #e7f4ea; border-left: 6px solid #2e8b45; }
.verdict.fails { background: #fdecea; border-left: 6px solid #c0392b; }
.verdict.stopped { background: #fff4e0; border-left: 6px solid #d68910; }
table { border-collapse: collapse; font-size: 0.92em; }
td, th { padding: 0.22em 0.8em 0.22em 0; text-align: left; vertical-align: top; }
th { font-weight: 600; border-bottom: 1px solid #ccd; }
td.name { color: #445; }
.tables { display: flex; gap: 2.2em; flex-wrap: wrap; align-items: flex-start; }
fieldset.off label:not(.check) { opacity: 0.45; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.figures figure { margin: 0; }
.figures img { max-width: 100%; border: 1px solid #e1e4e8; background: #fff; }
figcaption { font-size: 0.82em; color: #556; margin-top: 0.2em; max-width: 640px; }
ul.warnings li, li.warning { color: #8a4b00; }
progress { width: 100%; height: 1.3em; }
.muted { color: #667; font-size: 0.85em; }
a.download { display: inline-block; margin: 0.3em 0.8em 0.3em 0; }
tr.best td { font-weight: 600; background: #e7f4ea; }
.scroll { max-width: 100%; overflow-x: auto; }  /* a wide table scrolls inside its card on a phone */
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
  <p>Choose or upload an accelerogram, scale it, describe the statue and its pedestal, and run.
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
  <fieldset>
    <legend>Floor motion</legend>
    <label>bundled record
      <select id="record" name="record">
      {% for name in records %}
        <option value="{{ name }}"{% if name == form.record %} selected{% endif %}>{{ name }}</option>
      {% endfor %}
      </select>
    </label>
    <label>or upload a file <input id="upload" type="file" name="upload"></label>
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
    <label>duration (s) <input id="duration" name="duration" type="text" inputmode="decimal" value="{{ form.duration }}" placeholder="the record's length" title="at most {{ max_duration }} s on this server"></label>
  </fieldset>
  <fieldset>
    <legend>Statue</legend>
    <label>width B (m) <input id="statue_width" name="statue_width" type="text" inputmode="decimal" value="{{ form.statue_width }}"></label>
    <label>height H (m) <input id="statue_height" name="statue_height" type="text" inputmode="decimal" value="{{ form.statue_height }}"></label>
    <label>mass (kg) <input id="statue_mass" name="statue_mass" type="text" inputmode="decimal" value="{{ form.statue_mass }}"></label>
    <label>restitution r <input id="statue_restitution" name="statue_restitution" type="text" inputmode="decimal" value="{{ form.statue_restitution }}" placeholder="Housner's value"></label>
    <label>friction μs <input id="statue_mu_s" name="statue_mu_s" type="text" inputmode="decimal" value="{{ form.statue_mu_s }}" placeholder="never slides"></label>
    <label>friction μk <input id="statue_mu_k" name="statue_mu_k" type="text" inputmode="decimal" value="{{ form.statue_mu_k }}" placeholder="= μs"></label>
    <p class="hint">Friction under the statue: on the floor without a pedestal, on the pedestal's top (checked only) with one.</p>
  </fieldset>
  <fieldset id="pedestal-fields">
    <legend>Pedestal</legend>
    <label class="check"><input id="pedestal" name="pedestal" type="checkbox" value="on"{% if form.pedestal %} checked{% endif %}> the statue stands on a pedestal that can slide</label>
    <label>mass (kg) <input id="pedestal_mass" name="pedestal_mass" type="text" inputmode="decimal" value="{{ form.pedestal_mass }}"></label>
    <label>floor friction μs <input id="pedestal_mu_s" name="pedestal_mu_s" type="text" inputmode="decimal" value="{{ form.pedestal_mu_s }}"></label>
    <label>floor friction μk <input id="pedestal_mu_k" name="pedestal_mu_k" type="text" inputmode="decimal" value="{{ form.pedestal_mu_k }}" placeholder="= μs"></label>
    <label>width (m) <input id="pedestal_width" name="pedestal_width" type="text" inputmode="decimal" value="{{ form.pedestal_width }}" placeholder="optional"></label>
    <label>height (m) <input id="pedestal_height" name="pedestal_height" type="text" inputmode="decimal" value="{{ form.pedestal_height }}" placeholder="optional"></label>
  </fieldset>
  <div class="buttons"><button id="run" type="submit">Run</button></div>
  <fieldset style="margin-top:1em">
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
    <div class="buttons"><button id="sweep" class="secondary" type="submit" formaction="{{ url_for('start_sweep') }}">Run design sweep</button></div>
  </fieldset>
  <p id="busy">Running… (at most {{ timeout }} s)</p>
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
  form.addEventListener("submit", function () {
    // after the browser has collected the fields: disabled buttons are not submitted
    setTimeout(function () {
      document.querySelectorAll("#inputs button").forEach(function (b) { b.disabled = true; });
      document.getElementById("busy").style.display = "block";
    }, 0);
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
    <p class="muted">The bundled records are real accelerograms (PEER NGA and ESM); see <code>rocking records</code>.</p>
  </div>
{% endif %}
</section>
{% endblock %}
"""
)

_RESULT = """
<div class="card" id="result">
  <p id="verdict" class="verdict {{ result.verdict_class }}">{{ result.verdict }}</p>
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
  {% if result.summary.warnings %}
  <ul class="warnings" id="warnings">{% for w in result.summary.warnings %}<li>{{ w }}</li>{% endfor %}</ul>
  {% endif %}
</div>
<div class="card">
  <h2>Animation and plots</h2>
  <div class="figures">
    <figure>
      <img id="animation" alt="animation of the statue" src="{{ url_for('run_file', run_id=result.id, name=result.files.animation) }}">
      <figcaption>Played at {{ "%g"|format(result.animation_speed|round(2)) }}× real time; the colour tells the regime
        (rest, rock, slide, slide-rock).</figcaption>
    </figure>
    <figure>
      <img id="response-plot" alt="rotation, sliding and floor acceleration against time" src="{{ url_for('run_file', run_id=result.id, name=result.files.response) }}">
      <figcaption>Rotation θ/α, sliding u and floor acceleration against time; the background shows the regime, ticks mark impacts.</figcaption>
    </figure>
    <figure>
      <img id="energy-plot" alt="mechanical energy against time" src="{{ url_for('run_file', run_id=result.id, name=result.files.energy) }}">
      <figcaption>Mechanical energy relative to the floor, with the energy ledger.</figcaption>
    </figure>
  </div>
</div>
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
    "run.html": _RUN_PAGE,
    "sweep.html": _SWEEP,
}
