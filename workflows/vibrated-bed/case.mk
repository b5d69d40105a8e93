# Vibrated bed (thesis §4.6): 3,780 spheres in a quasi-2D box shaken at 25 Hz and 6 g.
#   make -f Makefile.cases vibrated-bed   generate and settle, vibrate 77 cycles (the thesis's
#                                         3.09 s; about half an hour on one core), 4 more cycles
#                                         filmed 8 times per cycle, post-process, report and plot
VBED_DIR := $(OUT)/vibrated-bed
VBED_SCENE := workflows/vibrated-bed/scene.toml
VBED_REPORT := scripts/vibrated_bed_report.py

$(VBED_DIR)/settled.h5: $(VBED_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(VBED_SCENE) --out $@

# One VTK frame per cycle at the same phase; the floor's (and every wall's) force every 100 steps,
# about 650 samples per cycle: enough to see when the bed leaves and hits the floor.
$(VBED_DIR)/vibrated.h5 $(VBED_DIR)/walls.csv $(VBED_DIR)/vtk/vibrate_particles.pvd &: $(VBED_SCENE) $(VBED_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(VBED_SCENE) --stage vibrate --in $(VBED_DIR)/settled.h5 --out $(VBED_DIR)/vibrated.h5 \
	  --vtk $(VBED_DIR)/vtk --wall-forces $(VBED_DIR)/walls.csv --wall-forces-every 100 \
	  --checkpoint-every 500000 --restart

# Four more cycles, eight frames per cycle: the arches forming and switching within two cycles.
$(VBED_DIR)/strobe.h5 $(VBED_DIR)/vtk/strobe_particles.pvd &: $(VBED_SCENE) $(VBED_DIR)/vibrated.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(VBED_SCENE) --stage strobe --in $(VBED_DIR)/vibrated.h5 --out $(VBED_DIR)/strobe.h5 \
	  --vtk $(VBED_DIR)/vtk --checkpoint-every 500000 --restart

# Particles coloured by their displacement over the 77 cycles, and the displacement field on a
# 2 mm grid (kernel width two diameters): open in ParaView with the VTK series in vtk/.
$(VBED_DIR)/displacement.vtu $(VBED_DIR)/fields.vti &: $(VBED_DIR)/settled.h5 $(VBED_DIR)/vibrated.h5 $(BIN)/post-macro
	$(BIN)/post-macro --reference $(VBED_DIR)/settled.h5 --in $(VBED_DIR)/vibrated.h5 --vtk $(VBED_DIR)/displacement.vtu \
	  --grid $(VBED_DIR)/fields.vti --cell 0.002 --width 0.002

VBED_PLOTS := $(VBED_DIR)/bed.png $(VBED_DIR)/strobe.png $(VBED_DIR)/summary.csv $(VBED_DIR)/surface.csv \
  $(VBED_DIR)/convection.csv
$(VBED_PLOTS) &: $(VBED_DIR)/vibrated.h5 $(VBED_DIR)/walls.csv $(VBED_DIR)/vtk/vibrate_particles.pvd \
    $(VBED_DIR)/vtk/strobe_particles.pvd $(VBED_REPORT) scripts/post_table.py
	$(PYTHON) $(VBED_REPORT) --end $(VBED_DIR)/vibrated.h5 --wall-forces $(VBED_DIR)/walls.csv \
	  --frames $(VBED_DIR)/vtk/vibrate_particles.pvd --strobe $(VBED_DIR)/vtk/strobe_particles.pvd \
	  --frequency 25 --acceleration 58.86 --summary $(VBED_DIR)/summary.csv --surface $(VBED_DIR)/surface.csv \
	  --displacement $(VBED_DIR)/convection.csv --png $(VBED_DIR)/bed.png --strobe-png $(VBED_DIR)/strobe.png

.PHONY: vibrated-bed vibrated-bed-outputs
vibrated-bed: build
	@$(MAKE) --no-print-directory -f $(SELF) vibrated-bed-outputs
	@echo "vibrated-bed: VTK series $(VBED_DIR)/vtk/vibrate_particles.pvd (one frame per cycle), vtk/strobe_particles.pvd (8 per cycle), walls vtk/*_walls.pvd"
	@echo "vibrated-bed: displacement $(VBED_DIR)/displacement.vtu, fields $(VBED_DIR)/fields.vti, plots $(VBED_DIR)/bed.png $(VBED_DIR)/strobe.png, figures $(VBED_DIR)/summary.csv"
vibrated-bed-outputs: $(VBED_PLOTS) $(VBED_DIR)/displacement.vtu
CASES += vibrated-bed
