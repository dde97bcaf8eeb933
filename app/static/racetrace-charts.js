// racetrace: plotly charts whose library is loaded after the first 3-D frame (see app/lazy_charts.py).
//
// Registers <racetrace-chart>, a stand-in for trame-plotly's <TramePlotly> that shows a short
// "loading" line until window.racetrace_charts.load(url) has fetched the trame-plotly bundle, then
// renders the real chart with the same attributes (data, layout, displayModeBar, ...).
(function () {
  const { defineComponent, h, shallowRef, markRaw } = window.Vue;
  const chart = shallowRef(null); // the TramePlotly component once its bundle has run
  let requested = false;

  function load(url) {
    if (requested) return;
    requested = true;
    const script = document.createElement("script");
    script.src = url;
    script.onload = function () {
      const found = {};
      window.trame_plotly.install({
        component(name, definition) {
          found[name] = definition;
          return this;
        },
      });
      chart.value = markRaw(found.TramePlotly);
      window.racetrace_charts.ready = true;
    };
    script.onerror = function () {
      console.error("racetrace: the chart library did not load from " + url);
    };
    document.head.appendChild(script);
  }

  const RacetraceChart = defineComponent({
    name: "RacetraceChart",
    inheritAttrs: false,
    setup(_props, { attrs }) {
      return () =>
        chart.value
          ? h(chart.value, attrs)
          : h("div", { class: "text-caption text-medium-emphasis pa-2" }, "loading chart\u2026");
    },
  });

  window.racetrace_charts = {
    ready: false,
    load,
    install(app) {
      app.component("racetrace-chart", RacetraceChart);
    },
  };
})();
