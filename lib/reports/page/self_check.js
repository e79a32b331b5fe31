// Counts what the browser drew of every chart and compares it with what the
// chart says it holds: series, points per series (parsed by the browser from
// the SVG), segments per bar; every point inside its picture; and every image
// decoded; and that a reader can read each chart: no label over another or
// struck through by a line, every series and guide line named by a label or a
// legend entry, every colour at least 3:1 against the page. It runs once the
// page has loaded, images included.
window.addEventListener('load', function () {
  var problems = [];
  var charts = document.querySelectorAll('g.chart');
  charts.forEach(function (chart) {
    var id = chart.getAttribute('data-chart') || '?';
    var box = chart.ownerSVGElement.viewBox.baseVal;
    var inside = function (p) { return isFinite(p.x) && isFinite(p.y) && p.x >= 0 && p.y >= 0 && p.x <= box.width && p.y <= box.height; };
    var series = chart.querySelectorAll('g.series'), bars = chart.querySelectorAll('g.bar');
    var drawn = series.length + bars.length;
    chart.setAttribute('data-drawn-series', drawn);
    if (String(drawn) !== chart.getAttribute('data-series')) problems.push(id + ': ' + drawn + ' series drawn, ' + chart.getAttribute('data-series') + ' said');
    series.forEach(function (s) {
      var geometry = s.getAttribute('data-geometry'), n = 0, points = [];
      if (geometry === 'line' || geometry === 'area') {
        var shape = s.querySelector(geometry === 'line' ? 'polyline' : 'polygon');
        for (var i = 0; shape && i < shape.points.numberOfItems; ++i) points.push(shape.points.getItem(i));
        n = geometry === 'line' ? points.length : points.length / 2;
      } else {
        s.querySelectorAll('circle').forEach(function (c) { points.push({x: c.cx.baseVal.value, y: c.cy.baseVal.value}); });
        n = points.length;
      }
      s.setAttribute('data-drawn-points', n);
      var name = id + '/' + s.getAttribute('data-name');
      if (String(n) !== s.getAttribute('data-points')) problems.push(name + ': ' + n + ' points drawn, ' + s.getAttribute('data-points') + ' said');
      if (!points.every(inside)) problems.push(name + ': a point outside the chart');
    });
    bars.forEach(function (b) {
      var n = b.querySelectorAll('rect').length;
      b.setAttribute('data-drawn-segments', n);
      if (String(n) !== b.getAttribute('data-segments')) problems.push(id + '/' + b.getAttribute('data-name') + ': ' + n + ' segments drawn');
    });
  });
  var images = document.querySelectorAll('img');
  images.forEach(function (img) { if (!img.complete || img.naturalWidth === 0) problems.push('an image that does not decode'); });
  // --- Legibility: labels apart, labels not struck through, every series
  // named, every colour readable (issue 55 item 2). ---
  // WCAG 2 relative luminance and contrast ratio of two CSS colours.
  var rgbOf = function (css) {
    var m = /rgba?\(\s*([\d.]+)[,\s]+([\d.]+)[,\s]+([\d.]+)(?:[,\s/]+([\d.]+))?/.exec(css || '');
    if (!m) return null;
    if (m[4] !== undefined && parseFloat(m[4]) === 0) return null;  // transparent: no colour drawn
    return [parseFloat(m[1]), parseFloat(m[2]), parseFloat(m[3])];
  };
  var luminance = function (rgb) {
    var c = rgb.map(function (v) { v /= 255; return v <= 0.03928 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4); });
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
  };
  var contrast = function (a, b) {
    var la = luminance(a), lb = luminance(b);
    return (Math.max(la, lb) + 0.05) / (Math.min(la, lb) + 0.05);
  };
  var hex = function (rgb) { return '#' + rgb.map(function (v) { return ('0' + Math.round(v).toString(16)).slice(-2); }).join(''); };
  var pageBackground = rgbOf(getComputedStyle(document.body).backgroundColor) || [255, 255, 255];
  // Where a segment (client coordinates) passes through a box shrunk by 1 px
  // (Liang-Barsky): touching an edge is not crossing.
  var crosses = function (p, q, box) {
    var l = box.left + 1, r = box.right - 1, t = box.top + 1, b = box.bottom - 1;
    if (r <= l || b <= t) return false;
    var t0 = 0, t1 = 1, dx = q.x - p.x, dy = q.y - p.y;
    var edges = [[-dx, p.x - l], [dx, r - p.x], [-dy, p.y - t], [dy, b - p.y]];
    for (var k = 0; k < 4; ++k) {
      var pk = edges[k][0], qk = edges[k][1];
      if (pk === 0) { if (qk < 0) return false; continue; }
      var u = qk / pk;
      if (pk < 0) { if (u > t1) return false; if (u > t0) t0 = u; } else { if (u < t0) return false; if (u < t1) t1 = u; }
    }
    return t0 <= t1;
  };
  // The segments of a <polyline> or <line>, in client coordinates.
  var segmentsOf = function (shape) {
    var m = shape.getScreenCTM(), svg = shape.ownerSVGElement, pts = [];
    var at = function (x, y) { var p = svg.createSVGPoint(); p.x = x; p.y = y; return p.matrixTransform(m); };
    if (shape.tagName === 'line') pts = [at(shape.x1.baseVal.value, shape.y1.baseVal.value), at(shape.x2.baseVal.value, shape.y2.baseVal.value)];
    else for (var i = 0; i < shape.points.numberOfItems; ++i) { var q = shape.points.getItem(i); pts.push(at(q.x, q.y)); }
    var out = [];
    for (var j = 1; j < pts.length; ++j) out.push([pts[j - 1], pts[j]]);
    return out;
  };
  charts.forEach(function (chart) {
    var id = chart.getAttribute('data-chart') || '?';
    var labels = [];
    chart.querySelectorAll('text').forEach(function (t) {
      var b = t.getBoundingClientRect();
      if (b.width > 0 && b.height > 0 && t.textContent.trim()) labels.push({b: b, text: t.textContent.trim(), node: t});
    });
    // Labels whole: none past its picture's edge, where it is cut off.
    var edge = chart.ownerSVGElement.getBoundingClientRect();
    labels.forEach(function (l) {
      if (l.b.left < edge.left - 1 || l.b.right > edge.right + 1 || l.b.top < edge.top - 1 || l.b.bottom > edge.bottom + 1)
        problems.push(id + ': the label "' + l.text + '" is cut off at the edge of the chart');
    });
    // Labels apart: no two boxes share more than a pixel each way.
    for (var i = 0; i < labels.length; ++i)
      for (var j = i + 1; j < labels.length; ++j) {
        var a = labels[i].b, c = labels[j].b;
        var w = Math.min(a.right, c.right) - Math.max(a.left, c.left), h = Math.min(a.bottom, c.bottom) - Math.max(a.top, c.top);
        if (w > 1 && h > 1) problems.push(id + ': labels overlap: "' + labels[i].text + '" and "' + labels[j].text + '"');
      }
    // Lines of data and guides (percentiles, budgets) never through a label.
    var lines = [];
    chart.querySelectorAll('g.series polyline, g.series line, g[data-value] line').forEach(function (shape) {
      var g = shape.closest('g.series, g[data-value]');
      var name = g.getAttribute('data-name') || (g.querySelector('title') || {}).textContent || g.getAttribute('class');
      lines.push({name: name, segments: segmentsOf(shape)});
    });
    labels.forEach(function (label) {
      lines.forEach(function (line) {
        if (line.segments.some(function (s) { return crosses(s[0], s[1], label.b); }))
          problems.push(id + ': the line of "' + line.name + '" crosses the label "' + label.text + '"');
      });
    });
    // Every series and every guide line named: by a label of its own, a
    // legend entry for it (data-for), or a label of the chart that is its name.
    var texts = labels.map(function (l) { return l.text; });
    var legendFor = function (key) {
      return Array.prototype.some.call(chart.querySelectorAll('[data-for]'), function (e) { return e.getAttribute('data-for') === key; });
    };
    chart.querySelectorAll('g.series').forEach(function (s) {
      var name = s.getAttribute('data-name');
      var own = Array.prototype.some.call(s.querySelectorAll('text'), function (t) { return t.textContent.trim(); });
      if (!own && !legendFor(name) && texts.indexOf(name) < 0) problems.push(id + '/' + name + ': a series no label or legend names');
    });
    chart.querySelectorAll('g[data-value]').forEach(function (g) {
      if (!g.querySelector('line')) return;
      var key = g.getAttribute('data-guide') || g.getAttribute('class');
      var own = Array.prototype.some.call(g.querySelectorAll('text'), function (t) { return t.textContent.trim(); });
      if (!own && !legendFor(key)) problems.push(id + ': a ' + g.getAttribute('class') + ' line at ' + g.getAttribute('data-value') + ' no label or legend names');
    });
    // Every colour a series, guide or label is drawn in: 3:1 or more against
    // the page (WCAG 2.1's for graphics), so that it can be told from it.
    var background = pageBackground;
    var backdrop = chart.ownerSVGElement.querySelector(':scope > rect');
    if (backdrop) background = rgbOf(getComputedStyle(backdrop).fill) || background;
    var seen = {};
    var judge = function (what, css) {
      var rgb = rgbOf(css);
      if (!rgb) return;
      var ratio = contrast(rgb, background), key = what + hex(rgb);
      if (ratio < 3 && !seen[key]) {
        seen[key] = true;
        problems.push(id + '/' + what + ': colour ' + hex(rgb) + ' has contrast ' + ratio.toFixed(2) + ':1 against the background ' + hex(background) + ' (3:1 needed)');
      }
    };
    chart.querySelectorAll('g.series, g.bar').forEach(function (s) {
      var name = s.getAttribute('data-name');
      s.querySelectorAll('polyline, line').forEach(function (e) { judge(name, getComputedStyle(e).stroke); });
      s.querySelectorAll('polygon, rect, circle').forEach(function (e) {
        var label = e.querySelector('title') ? e.querySelector('title').textContent.replace(/:.*/, '') : name;
        judge(s.classList.contains('bar') ? label : name, getComputedStyle(e).fill);
      });
    });
    chart.querySelectorAll('g[data-value] line').forEach(function (e) {
      judge((e.closest('g[data-value]').querySelector('title') || {}).textContent || 'guide', getComputedStyle(e).stroke);
    });
    labels.forEach(function (l) { judge('label "' + l.text + '"', getComputedStyle(l.node).fill); });
    chart.querySelectorAll('[data-for] rect, [data-for] line').forEach(function (e) {
      var key = e.closest('[data-for]').getAttribute('data-for');
      judge('legend ' + key, e.tagName === 'line' ? getComputedStyle(e).stroke : getComputedStyle(e).fill);
    });
  });
  // Nothing wider than the page's column: a table or chart past it is cut off
  // or scrolls sideways (a compare of every mode at 1280 px).
  var column = document.body.getBoundingClientRect();
  var right = column.right - parseFloat(getComputedStyle(document.body).paddingRight) + 1;
  document.querySelectorAll('table, svg, img, pre, p, h1, h2').forEach(function (e) {
    var box = e.getBoundingClientRect();
    if (box.right > right) problems.push(e.tagName.toLowerCase() + (e.id ? '#' + e.id : e.className && e.className.baseVal === undefined && e.className ? '.' + e.className : '') + ' overflows the page by ' + Math.round(box.right - right) + ' px');
  });
  var expected = document.body.getAttribute('data-charts');
  if (String(charts.length) !== expected) problems.push(charts.length + ' charts drawn, ' + expected + ' made');
  document.body.setAttribute('data-report-check', problems.length ? 'failed: ' + problems.join('; ') :
    'ok ' + charts.length + ' charts' + (images.length ? ', ' + images.length + ' images' : ''));
});
