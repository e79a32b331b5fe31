// Records script errors where a reader (and the browser test) finds them.
window.addEventListener('error', function (e) {
  var html = document.documentElement;
  html.setAttribute('data-js-errors', (html.getAttribute('data-js-errors') || '') + e.message + '; ');
});
