// The report's figures (plotly, inlined above) and the colour toggle of the 3-D view (equimesh/io/_report.py).
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("report-data").textContent);
  const config = { responsive: true, displaylogo: false };
  const view = document.getElementById("view");
  const drawn = Object.entries(data.figures).map(([id, figure]) =>
    Plotly.newPlot(document.getElementById(id), figure.data, figure.layout, config)
  );
  // Each member trace carries its members' deviation from l, per vertex, as customdata.
  const deviations = data.members.map((i) => data.figures.view.data[i].customdata);
  const scale = data.deviation;

  function colourBy(mode) {
    const update =
      mode === "deviation"
        ? {
            "line.color": deviations,
            "line.colorscale": [scale.colorscale],
            "line.cmin": -scale.limit,
            "line.cmax": scale.limit,
            "line.showscale": data.members.map((i) => i === 0),
            "line.colorbar": {
              title: { text: "(L - l) / l", side: "top" },
              tickformat: "+.1%",
              orientation: "h",
              x: 0.5,
              y: 0,
              len: 0.5,
              thickness: 12,
            },
          }
        : { "line.color": data.colours, "line.showscale": false };
    return Plotly.restyle(view, update, data.members);
  }

  const initial = window.location.hash === "#deviation" ? "deviation" : "class";
  document.querySelectorAll('input[name="colour"]').forEach((input) => {
    input.checked = input.value === initial;
    input.addEventListener("change", () => colourBy(input.value));
  });
  Promise.all(drawn)
    .then(() => (initial === "class" ? null : colourBy(initial)))
    .then(() => {
      document.documentElement.dataset.ready = "true";
    });
})();
