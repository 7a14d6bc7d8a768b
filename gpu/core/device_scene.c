/* device_scene.c — the plan flattened for a device (device_scene.h), shared by the cl and gl
 * backends so both read the same records. */
#include "device_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/constants.h"
#include "mesh.h"
#include "scene_internal.h"

void ics_device_scene_destroy(ics_device_scene *d) {
  free(d->fz), free(d->fcode), free(d->fgrad), free(d->fspan), free(d->obj), free(d->tt);
  free(d->perm), free(d->grids), free(d->inside);
  memset(d, 0, sizeof *d);
}

void ics_device_camera(const ics_plan *P, double cam[ICS_DEV_CAM]) {
  const ics_camera *cm = &P->cam;
  for (int i = 0; i < 3; i++)
    cam[CAM_EYE + i] = cm->eye[i], cam[CAM_R + i] = cm->r[i], cam[CAM_U + i] = cm->u[i],
    cam[CAM_F + i] = cm->f[i];
  cam[CAM_H] = cm->height;
  cam[CAM_W] = cm->height * P->W / P->H;
  cam[CAM_TH] = P->tan_half_fov;
  cam[CAM_ASP] = (double)P->W / P->H;
  cam[CAM_PROJ] = cm->projection == ICS_PROJ_PERSPECTIVE;
}

ics_status ics_device_scene_create(ics_device_scene *d, const ics_plan *P, int fragments) {
  memset(d, 0, sizeof *d);
  const ics_scene *sc = P->scene;
  size_t npx = (size_t)P->Wb * P->Hb, nfrag = fragments ? P->ldi.nfrag : 0, ntt = 0, ncells = 0;
  int inside = fragments && P->nvol;
  for (int i = 0; i < sc->nobjects; i++) {
    const ics_material *m = &sc->materials[sc->objects[i].material];
    ntt += (size_t)m->ntransfer;
    if (m->detail.fn == ICS_DETAIL_GRID)
      ncells += (size_t)m->detail.size[0] * (size_t)m->detail.size[1] * (size_t)m->detail.size[2];
  }
  d->nfrag = nfrag ? nfrag : 1;
  d->nobj = sc->nobjects ? (size_t)sc->nobjects : 1;
  d->ntt = ntt ? ntt : 1;
  d->ncells = ncells ? ncells : 1;
  d->fz = malloc(sizeof *d->fz * d->nfrag);
  d->fcode = malloc(sizeof *d->fcode * d->nfrag);
  d->fgrad = malloc(2 * sizeof *d->fgrad * d->nfrag);
  d->fspan = malloc(d->nfrag);
  d->obj = calloc(d->nobj * ICS_DEV_OBJ_STRIDE, sizeof *d->obj);
  d->tt = calloc(5 * d->ntt, sizeof *d->tt);
  d->perm = calloc(d->nobj, 512);
  d->grids = malloc(sizeof *d->grids * d->ncells);
  d->inside = inside ? malloc(sizeof *d->inside * npx) : NULL;
  if (!d->fz || !d->fcode || !d->fgrad || !d->fspan || !d->obj || !d->tt || !d->perm ||
      !d->grids || (inside && !d->inside)) {
    ics_device_scene_destroy(d);
    return ICS_ERR_NOMEM;
  }
  for (size_t f = 0; f < nfrag; f++) {
    const ics_fragment *fr = &P->ldi.frag[f];
    d->fz[f] = fr->z;
    d->fcode[f] = fr->code;
    d->fgrad[2 * f] = (float)(fr->grad[0] / ICS_FRAG_GRAD_SCALE); /* exact: int16 / 64 */
    d->fgrad[2 * f + 1] = (float)(fr->grad[1] / ICS_FRAG_GRAD_SCALE);
    d->fspan[f] = fr->span;
  }
  if (!nfrag) d->fz[0] = 0, d->fcode[0] = 0, d->fgrad[0] = d->fgrad[1] = 0, d->fspan[0] = 0;
  /* objects (the O_* offsets of the device programs), their transfer rows and permutations */
  size_t cell = 0;
  for (int i = 0, row = 0; i < sc->nobjects; i++) {
    const ics_material *m = &sc->materials[sc->objects[i].material];
    const ics_detail *dt = &m->detail;
    double *o = d->obj + (size_t)i * ICS_DEV_OBJ_STRIDE;
    o[O_OPACITY] = m->opacity;
    for (int c = 0; c < 3; c++) o[O_COLOR + c] = m->color[c], o[O_TRANSPORT + c] = m->transport[c];
    o[O_EXTINCTION] = m->extinction;
    o[O_VOLBIT] = P->vol_bit[i];
    o[O_DETAIL] = dt->fn;
    o[O_FREQ] = dt->frequency, o[O_LACUNARITY] = dt->lacunarity, o[O_GAIN] = dt->gain;
    o[O_OFFSET] = dt->offset, o[O_TIME] = dt->time, o[O_SCALE] = dt->scale;
    o[O_BIAS] = dt->bias, o[O_OCTAVES] = dt->octaves;
    o[O_NTRANSFER] = m->ntransfer, o[O_TRANSFER] = row;
    memcpy(d->tt + 5 * (size_t)row, m->transfer, sizeof(double) * 5 * (size_t)m->ntransfer);
    row += m->ntransfer;
    if (P->vol_bit[i] >= 0) d->vol_obj[P->vol_bit[i]] = i;
    if (dt->fn != ICS_DETAIL_NONE && P->detail)
      memcpy(d->perm + 512 * (size_t)i, P->detail[i].perm, 512);
    if (dt->fn == ICS_DETAIL_GRID && P->detail) { /* its cells and the object's box */
      size_t n = (size_t)dt->size[0] * (size_t)dt->size[1] * (size_t)dt->size[2];
      memcpy(d->grids + cell, dt->grid, sizeof *d->grids * n);
      o[O_GRID] = (double)cell;
      for (int a = 0; a < 3; a++)
        o[O_GRID_N + a] = dt->size[a], o[O_GRID_LO + a] = P->detail[i].lo[a],
        o[O_GRID_HI + a] = P->detail[i].hi[a];
      cell += n;
    }
  }
  if (!ncells) d->grids[0] = 0;
  if (d->inside) {
    if (P->ldi.inside0) memcpy(d->inside, P->ldi.inside0, sizeof *d->inside * npx);
    else memset(d->inside, 0, sizeof *d->inside * npx);
  }
  ics_device_camera(P, d->cam);
  for (int l = 0; l < P->nlights; l++) {
    const ics_light *lt = &sc->lights[l];
    for (int c = 0; c < 3; c++) d->lcol[3 * l + c] = lt->color[c] * lt->weight;
    d->lmu[2 * l] = lt->mean[0], d->lmu[2 * l + 1] = lt->mean[1];
    d->signed_l[l] = P->kernels[l].comp == ICS_RC_SIGNED;
    d->blur[l] = ics_plan_light_blur(P, l);
  }
  return ICS_OK;
}

void ics_device_geometry_destroy(ics_device_geometry *g) {
  free(g->geo), free(g->node_box), free(g->node_link), free(g->tris);
  memset(g, 0, sizeof *g);
}

ics_status ics_device_geometry_create(ics_device_geometry *g, const ics_plan *P) {
  memset(g, 0, sizeof *g);
  const ics_scene *sc = P->scene;
  size_t nnodes = 0, ntris = 0;
  for (int i = 0; i < sc->nobjects; i++)
    if (sc->objects[i].shape == ICS_SHAPE_MESH) {
      int nn, nt;
      ics_mesh_flat_counts(sc->objects[i].mesh, &nn, &nt);
      nnodes += (size_t)nn, ntris += (size_t)nt;
    }
  g->nobj = sc->nobjects ? (size_t)sc->nobjects : 1;
  g->nnodes = nnodes ? nnodes : 1;
  g->ntris = ntris ? ntris : 1;
  g->geo = calloc(g->nobj * ICS_DEV_GEO_STRIDE, sizeof *g->geo);
  g->node_box = calloc(6 * g->nnodes, sizeof *g->node_box);
  g->node_link = calloc(4 * g->nnodes, sizeof *g->node_link);
  g->tris = calloc(9 * g->ntris, sizeof *g->tris);
  if (!g->geo || !g->node_box || !g->node_link || !g->tris) {
    ics_device_geometry_destroy(g);
    return ICS_ERR_NOMEM;
  }
  int node_base = 0, tri_base = 0;
  for (int i = 0; i < sc->nobjects; i++) {
    const ics_object *o = &sc->objects[i];
    double *r = g->geo + (size_t)i * ICS_DEV_GEO_STRIDE;
    r[G_SHAPE] = o->shape;
    memcpy(r + G_CENTER, o->center, sizeof o->center);
    memcpy(r + G_AXES, o->ax, sizeof o->ax);
    memcpy(r + G_HALF, o->half, sizeof o->half);
    r[G_VOLBIT] = P->vol_bit[i];
    r[G_BVH_ROOT] = -1;
    if (o->shape == ICS_SHAPE_MESH) {
      int nn, nt;
      ics_mesh_flat_counts(o->mesh, &nn, &nt);
      ics_mesh_flatten(o->mesh, node_base, tri_base, g->node_box + 6 * (size_t)node_base,
                       g->node_link + 4 * (size_t)node_base, g->tris + 9 * (size_t)tri_base);
      r[G_BVH_ROOT] = node_base;
      r[G_MERGE_EPS] = ics_mesh_merge_eps(o->mesh);
      node_base += nn, tri_base += nt;
    }
  }
  return ICS_OK;
}
