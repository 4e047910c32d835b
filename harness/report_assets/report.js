// Fills every <img data-key> from the page's image table (each picture is stored once, however
// many cases show it) and drives the golden/new sliders. No network, no external scripts.
(function () {
  const images = JSON.parse(document.getElementById("images").textContent);
  for (const img of document.querySelectorAll("img[data-key]")) {
    img.src = "data:image/png;base64," + images[img.dataset.key];
  }
  for (const slider of document.querySelectorAll(".slider")) {
    const top = slider.querySelector("img.top");
    const input = slider.querySelector("input");
    input.addEventListener("input", () => {
      top.style.clipPath = "inset(0 " + (100 - input.value) + "% 0 0)";
    });
  }
})();
