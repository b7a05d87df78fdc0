// Click a column head of a .sortable table to sort by it (again to reverse).
// Cells may carry data-sort (the raw number) so 2×10⁻⁵ sorts as a number.
(function () {
  function key(cell) {
    var raw = cell.getAttribute("data-sort");
    var text = (raw !== null ? raw : cell.textContent).trim();
    var number = parseFloat(text);
    return (text !== "" && isFinite(number) && String(Number(text)) !== "NaN")
      ? [0, number] : [1, text.toLowerCase()];
  }
  function compare(a, b) {
    if (a[0] !== b[0]) return a[0] - b[0];  // numbers before text
    return a[1] < b[1] ? -1 : a[1] > b[1] ? 1 : 0;
  }
  document.querySelectorAll("table.sortable").forEach(function (table) {
    var heads = table.tHead ? table.tHead.rows[0].cells : [];
    Array.prototype.forEach.call(heads, function (th, column) {
      th.addEventListener("click", function () {
        var direction = th.getAttribute("data-dir") === "asc" ? -1 : 1;
        Array.prototype.forEach.call(heads, function (h) { h.removeAttribute("data-dir"); });
        th.setAttribute("data-dir", direction === 1 ? "asc" : "desc");
        var body = table.tBodies[0];
        var rows = Array.prototype.slice.call(body.rows);
        rows.sort(function (a, b) { return direction * compare(key(a.cells[column]), key(b.cells[column])); });
        rows.forEach(function (row) { body.appendChild(row); });
      });
    });
  });
})();
