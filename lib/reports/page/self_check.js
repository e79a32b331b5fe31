// Counts what the browser drew of every chart and compares it with what the
// chart says it holds: series, points per series (parsed by the browser from
// the SVG), segments per bar; every point inside its picture; and every image
// decoded. It runs once the page has loaded, images included.
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
  // No two labels of a chart on top of each other.
  charts.forEach(function (chart) {
    var boxes = [];
    chart.querySelectorAll('text').forEach(function (t) {
      var b = t.getBoundingClientRect();
      if (b.width > 0 && b.height > 0) boxes.push({b: b, text: t.textContent});
    });
    for (var i = 0; i < boxes.length; ++i)
      for (var j = i + 1; j < boxes.length; ++j) {
        var a = boxes[i].b, c = boxes[j].b;
        var w = Math.min(a.right, c.right) - Math.max(a.left, c.left), h = Math.min(a.bottom, c.bottom) - Math.max(a.top, c.top);
        if (w > 2 && h > 2) problems.push((chart.getAttribute('data-chart') || '?') + ': labels overlap: "' + boxes[i].text + '" and "' + boxes[j].text + '"');
      }
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
