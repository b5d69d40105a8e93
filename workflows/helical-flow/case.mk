# Helical flow (thesis §4.3): an auger (a cylinder with a helical ramp) turning at 95 rpm in a box
# of 28,800 spheres lifts them.
#   make -f Makefile.cases helical-flow   fill and settle the box around the still auger, turn it
#                                         for the thesis's 2.9 s, report the flow rate up the ramp,
#                                         the drive torque and power, and plot them
#                                         (workflows/helical-flow/README.md: choices, cost, results)
HEL_DIR := $(OUT)/helical-flow
HEL_SCENE := workflows/helical-flow/scene.toml
HEL_REPORT := scripts/helical_flow_report.py
# The geometry of the scene's auger, for the report: shaft and flight radii, pitch [m], speed, and
# the counting plane (0.4 m: mid-depth of the settled bed, a turn above the flight's lowest edge).
HEL_GEOMETRY := --walls shaft,cap,ramp --rpm -95 --r-in 0.1 --r-out 0.3 --pitch 0.3 --plane 0.4

$(HEL_DIR)/settled.h5: $(HEL_SCENE) $(BIN)/gen-primary
	$(BIN)/gen-primary --scene $(HEL_SCENE) --out $@

# One VTK frame every 0.02 s (velocity, displacement); every wall's force and torque every 100 steps.
$(HEL_DIR)/spun.h5 $(HEL_DIR)/walls.csv $(HEL_DIR)/vtk/spin_particles.pvd &: $(HEL_SCENE) $(HEL_DIR)/settled.h5 $(BIN)/run-stage
	$(BIN)/run-stage --scene $(HEL_SCENE) --stage spin --in $(HEL_DIR)/settled.h5 --out $(HEL_DIR)/spun.h5 \
	  --vtk $(HEL_DIR)/vtk --wall-forces $(HEL_DIR)/walls.csv --wall-forces-every 100 \
	  --checkpoint-every 100000 --restart

HEL_PLOTS := $(HEL_DIR)/helical.png $(HEL_DIR)/flow.csv $(HEL_DIR)/power.csv $(HEL_DIR)/summary.csv
$(HEL_PLOTS) &: $(HEL_DIR)/settled.h5 $(HEL_DIR)/spun.h5 $(HEL_DIR)/walls.csv $(HEL_DIR)/vtk/spin_particles.pvd \
    $(HEL_REPORT) scripts/plane_flux.py scripts/post_table.py
	$(PYTHON) $(HEL_REPORT) --start $(HEL_DIR)/settled.h5 --end $(HEL_DIR)/spun.h5 \
	  --frames $(HEL_DIR)/vtk/spin_particles.pvd --wall-forces $(HEL_DIR)/walls.csv $(HEL_GEOMETRY) --skip 0.5 \
	  --flux $(HEL_DIR)/flow.csv --power $(HEL_DIR)/power.csv --summary $(HEL_DIR)/summary.csv --png $(HEL_DIR)/helical.png

.PHONY: helical-flow helical-flow-outputs
helical-flow: build
	@$(MAKE) --no-print-directory -f $(SELF) helical-flow-outputs
	@echo "helical-flow: VTK series $(HEL_DIR)/vtk/spin_particles.pvd (velocity), walls vtk/spin_walls.pvd"
	@echo "helical-flow: plot $(HEL_DIR)/helical.png, flow rate $(HEL_DIR)/flow.csv, torque and power $(HEL_DIR)/power.csv, figures $(HEL_DIR)/summary.csv"
helical-flow-outputs: $(HEL_PLOTS)
CASES += helical-flow
