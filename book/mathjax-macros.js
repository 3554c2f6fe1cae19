// TeX macros for the book's formulas. KaTeX has no \dddot (a third time
// derivative), and MathJax 2's is only in its AMS extension, so the book
// defines its own. MathJax 2 reads `window.MathJax` as its configuration
// when it starts; if it has already started, the macro is added through its API.
(function () {
  var macros = {
    dddot: ["\\overset{\\,\\cdot\\!\\cdot\\!\\cdot}{#1}", 1],
  };
  if (window.MathJax && window.MathJax.Hub) {
    window.MathJax.Hub.Config({ TeX: { Macros: macros } });
    window.MathJax.Hub.Queue(["Typeset", window.MathJax.Hub]);
  } else {
    window.MathJax = { TeX: { Macros: macros } };
  }
})();
