// Which workgroup of the image an invocation of dispatch_rows (frame.hpp) works on. Mesa's
// llvmpipe hands each of its compute threads one contiguous run of a dispatch's workgroups, in
// row order, so where a frame's top costs less than its bottom (sky above, ground below) one
// thread idles while the other finishes: Alchemy's halves of the village street at 1080p took
// 103 and 169 ms (bench/README.md). Dispatch row j stands for image row
// (j % rows) * shares + j / rows, rows = the dispatch's rows / shares: each thread's run covers
// every shares-th row of the whole image, and the threads work on neighbouring rows at once,
// whose taps share the cache. u_dispatch_shares is 1 on a GPU, the identity. dispatch_rows
// makes the dispatch's rows a multiple of it, so the map is one to one; the rows past the
// image are the shader's to skip, as are the spare invocations of a partial workgroup.
uniform int u_dispatch_shares;

uvec2 image_workgroup() {
  uint shares = uint(max(u_dispatch_shares, 1));
  uint rows = max(gl_NumWorkGroups.y / shares, 1u);
  uint j = gl_WorkGroupID.y;
  return uvec2(gl_WorkGroupID.x, (j % rows) * shares + j / rows);
}
