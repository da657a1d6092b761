<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="en_US">
<context>
    <name>DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="48"/>
        <source>Thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="48"/>
        <source>Index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="49"/>
        <source>Middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="49"/>
        <source>Ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="50"/>
        <source>Little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="26"/>
        <source>thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="26"/>
        <source>index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="27"/>
        <source>middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="27"/>
        <source>ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="28"/>
        <source>little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ReviewWindow</name>
    <message>
        <location filename="../ui/review_window.cpp" line="34"/>
        <source>thumb</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="34"/>
        <source>index</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="35"/>
        <source>middle</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="35"/>
        <source>ring</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="36"/>
        <source>little</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="414"/>
        <source>Simulated HandHIRO (scripted palpation)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="415"/>
        <source>Mouse palpation (no robot)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="416"/>
        <source>Device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="417"/>
        <source>HandHIRO address</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="418"/>
        <source>Loop jitter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="419"/>
        <source>The HandHIRO network link is chosen at start: palpation-trainer --device emulator, or --device handhiro --robot ADDRESS:PORT.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="432"/>
        <source>attached</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="432"/>
        <source>released</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="434"/>
        <source>%1 us (max over 0.5 s)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::EventText</name>
    <message>
        <location filename="../ui/event_text.cpp" line="21"/>
        <source>Patient&apos;s tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="23"/>
        <source>%1 at (%2, %3, %4) cm, %5 kPa</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="24"/>
        <source>Sphere</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="24"/>
        <source>Ellipsoid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="26"/>
        <source>Painted tumour %1, %2 kPa</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="31"/>
        <source>%1 (%n elements)</source>
        <translation>
            <numerusform>%1 (%n element)</numerusform>
            <numerusform>%1 (%n elements)</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="36"/>
        <source>Add tumour: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="37"/>
        <source>Remove tumour: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="38"/>
        <source>Erase</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="38"/>
        <source>Paint</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="40"/>
        <source>Erase stroke (%n elements)</source>
        <translation>
            <numerusform>Erase stroke (%n element)</numerusform>
            <numerusform>Erase stroke (%n elements)</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="40"/>
        <source>Paint stroke (%n elements)</source>
        <translation>
            <numerusform>Paint stroke (%n element)</numerusform>
            <numerusform>Paint stroke (%n elements)</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="43"/>
        <source>Undo: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="48"/>
        <source>loading patient: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="50"/>
        <source>patient loaded: %1 nodes, %2 tetrahedra, backend %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="51"/>
        <source>patient not loaded: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="52"/>
        <source>solver/contact parameters changed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="56"/>
        <source>device: mouse palpation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="57"/>
        <source>device: scripted hand</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="58"/>
        <source>trainee mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="59"/>
        <source>instructor mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="60"/>
        <source>guided practice (trainee)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="61"/>
        <source>exam (trainee)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="65"/>
        <source>trainee mark %1 at (%2, %3, %4) cm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="68"/>
        <source>trainee mark %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="69"/>
        <source>, %1 % confident</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="70"/>
        <source>: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="73"/>
        <source>guided practice ended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="73"/>
        <source>exam ended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="74"/>
        <source>backend error: %1; continuing on the CPU from rest (forces held, then blended)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="75"/>
        <source>simulation diverged (%1): body reset to rest (forces held, then blended)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="77"/>
        <source>simulation stopped: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="86"/>
        <source>small</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="87"/>
        <source>medium</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="88"/>
        <source>large</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="89"/>
        <source>wide and flat</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="90"/>
        <source>narrow and projecting</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="93"/>
        <source>Healthy breast, %1 (%2 mL), the paper&apos;s size, no tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="94"/>
        <source>Healthy breast, %1 (%2 mL), no tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="96"/>
        <source>The paper&apos;s case: medium breast, tumour 3 cm diameter, 107 kPa, 1.5 cm below the skin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>soft</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>hard</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>firm</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="99"/>
        <source>Medium breast, %1 tumour %2 cm diameter (%3 kPa), centre %4 cm below the skin</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="107"/>
        <source>Export plot as PNG</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="107"/>
        <source>PNG images (*.png)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="111"/>
        <source>Export forces as CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="111"/>
        <source>CSV files (*.csv)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="118"/>
        <source>|F| vs time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="119"/>
        <source>Fz vs time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="120"/>
        <source>Fz vs x (Fig. 6)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="121"/>
        <source>solid: sent to the device (limit %1 N, dotted); dashed: simulated contact force</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="122"/>
        <source>Force magnitude per finger (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="123"/>
        <source>Fz per finger (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="124"/>
        <source>Fz (N) against finger x (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="130"/>
        <source>%1 (simulated)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="135"/>
        <location filename="../ui/force_plots.cpp" line="136"/>
        <source>device limit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="137"/>
        <source>Resume</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="137"/>
        <source>Pause</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="138"/>
        <source>Export PNG...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="139"/>
        <source>Export CSV...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="141"/>
        <source>The device renders the simulated force times the force scale, chosen when the patient loads: a deep press (%1 % of the tissue thickness) over the stiffest part of the patient maps to %2 % of the device&apos;s limit, so that the tumour&apos;s extra force stays within the device&apos;s range. Device limit %3 N = %4 N simulated. Solid lines: sent (device units); dashed: simulated.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="157"/>
        <source>Force scale %1 (device configuration): %2 N simulated -&gt; %3 N at the device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="162"/>
        <source>Force scale %1: deep press %2 N simulated -&gt; %3 N at the device (limit %4 N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="167"/>
        <source>Force scale 1: simulated forces sent unscaled</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ImportDialog</name>
    <message>
        <location filename="../ui/import_dialog.cpp" line="98"/>
        <source>Scanned breast surface</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="99"/>
        <source>Surface meshes (*.stl *.obj *.ply);;All files (*)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="109"/>
        <source>Cancelling...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="124"/>
        <source>Import a scanned breast</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="130"/>
        <source>Patient name</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="131"/>
        <source>Resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="132"/>
        <source>File units</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="133"/>
        <source>Chest-wall plane</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="137"/>
        <source>Scan file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="138"/>
        <source>n (into the chest), d (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="143"/>
        <source>Browse...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="144"/>
        <source>Coarse (real time on a CPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="145"/>
        <source>Paper (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="146"/>
        <source>Fine (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="147"/>
        <source>metres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="148"/>
        <source>centimetres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="149"/>
        <source>millimetres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="150"/>
        <source>Find automatically (the largest flat region)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="151"/>
        <source>Untick to give the plane n . x = d by hand: n points out of the body into the chest.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="152"/>
        <source>Import</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="153"/>
        <source>Cancel import</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="154"/>
        <source>Save as patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="155"/>
        <source>Close</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="181"/>
        <source>Choose a scan file (STL, OBJ or PLY) first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="190"/>
        <source>The base plane&apos;s normal must not be zero.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="205"/>
        <source>Reading %1...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="220"/>
        <source>Cancelled: nothing was saved.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="226"/>
        <source>Import failed: nothing was saved.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="231"/>
        <source>Done in %1 s (meshing %2 s).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="233"/>
        <source>%1 nodes, %2 tetrahedra. Repairs: %3. Base plane %4: n = (%5, %6, %7), %8 cm².</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="236"/>
        <source>none</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="237"/>
        <source>found</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="237"/>
        <source>given</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="246"/>
        <source>No patient library is open.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="254"/>
        <source>Give the patient a name.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="259"/>
        <source>A patient named &quot;%1&quot; exists already in %2: choose another name.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="270"/>
        <source>Saved as &quot;%1&quot; in the patient library.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::MainWindow</name>
    <message>
        <location filename="../ui/main_window.cpp" line="145"/>
        <source>Mouse palpation: move over the breast; the wheel or a downward drag presses the fingertip in.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="155"/>
        <source>No element lies inside that shape: nothing added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="234"/>
        <source>This session is not recorded: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="236"/>
        <source>Recovered interrupted recordings: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="238"/>
        <source>Patient library not available (built-in phantoms only): %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="278"/>
        <source>no patient library is open: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="313"/>
        <source>No fingertip on the breast: nothing marked.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="313"/>
        <source>This session is not recorded: nothing marked.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="355"/>
        <source>Patient &quot;%1&quot; saved; choose it and Load patient to palpate it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="368"/>
        <source>Open a session recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="369"/>
        <source>Session recordings (*.palrec *.prec);;All files (*)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="372"/>
        <source>Cannot open the recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="376"/>
        <source>Save screenshot</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="376"/>
        <source>PNG images (*.png)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="406"/>
        <location filename="../ui/main_window.cpp" line="566"/>
        <source>Stereo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="416"/>
        <source>Eye separation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="416"/>
        <source>Eye angle (degrees):</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="495"/>
        <source>End the exam now? No more marks can be made after it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="552"/>
        <source>Palpation Trainer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="553"/>
        <source>&amp;File</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="554"/>
        <source>&amp;Open recording...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="555"/>
        <source>Mark lump here (M)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="556"/>
        <source>Trainee: &quot;I feel a lump here&quot;: marks the index fingertip&apos;s position in the recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="557"/>
        <source>Save &amp;screenshot...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="558"/>
        <source>&amp;Quit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="559"/>
        <source>&amp;Edit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="560"/>
        <source>Undo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="561"/>
        <source>Redo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="562"/>
        <source>&amp;View</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="563"/>
        <source>Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="564"/>
        <source>Oblique</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="564"/>
        <source>Top</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="564"/>
        <source>Side</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="564"/>
        <source>Front</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="567"/>
        <source>Mono</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="567"/>
        <source>Anaglyph (red/cyan)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="567"/>
        <source>Side by side</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="567"/>
        <source>Interlaced</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="567"/>
        <source>Quad-buffer (shutter glasses)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="569"/>
        <source>Eye separation...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="570"/>
        <source>Mirrored (half-mirror display)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="571"/>
        <source>Fast rendering (software OpenGL)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="572"/>
        <source>A lighter 3-D view: plain background, no highlights on the skin, an unlit chest. On by itself when the computer draws OpenGL in software.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="574"/>
        <source>Displacement colour map</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="575"/>
        <source>Stress colour map (von Mises)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="576"/>
        <source>Show tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="577"/>
        <source>Panels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="578"/>
        <source>&amp;Mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="579"/>
        <source>Instructor mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="588"/>
        <source>Coverage overlay</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="589"/>
        <source>Colours the skin by the highest pressure reached: yellow light, orange medium, red deep. Not shown in an exam.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="591"/>
        <source>Clear coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="592"/>
        <source>Trainee progress...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="593"/>
        <source>Each trainee&apos;s exams over time and the class&apos;s results</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="597"/>
        <source>Tools</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="598"/>
        <source>Coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="599"/>
        <source>Camera / scripted hand</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="600"/>
        <source>Palpate with the mouse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="674"/>
        <source>Trainee</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="675"/>
        <source>Who is the trainee? Choose a name or type a new one (empty: anonymous, no result stored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="693"/>
        <source>Trainee not added to the library: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="704"/>
        <source>Patient library not available: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="737"/>
        <source>The exam&apos;s result is not stored: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="763"/>
        <source>Coverage: %1 none %2 light %3 %4 medium %5 %6 deep %7</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="845"/>
        <source>, trainee %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="916"/>
        <source>Not recording</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="917"/>
        <source>Recording stopped: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="918"/>
        <source>Recording (%1 marks)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="130"/>
        <location filename="../ui/main_window.cpp" line="601"/>
        <source>Patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="307"/>
        <source>The exam has ended: nothing marked.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="322"/>
        <source>Mark %1: &quot;I feel a lump here&quot; at (%2, %3, %4) cm, %5 % confident, recorded.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="580"/>
        <source>The instructor&apos;s view: every panel, the answer included. From a trainee mode it asks for a confirmation.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="582"/>
        <source>Guided practice</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="583"/>
        <source>Trainee: palpate and mark; the instructor&apos;s panels are hidden.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="584"/>
        <source>Exam</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="585"/>
        <source>Trainee examined: palpate and mark; the answer stays hidden until the exam ends.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="586"/>
        <source>End exam</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="587"/>
        <source>Stops the exam: no more marks.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="594"/>
        <source>Possible (25 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="594"/>
        <source>Likely (50 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="594"/>
        <source>Probable (75 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="594"/>
        <source>Certain (100 %)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="596"/>
        <source>How sure you are of the next mark</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="602"/>
        <source>Tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="603"/>
        <source>Forces</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="604"/>
        <source>Simulation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="605"/>
        <source>Device</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="644"/>
        <source>Return to instructor mode? This ends the trainee&apos;s session and shows the answer, the patient&apos;s details and every panel. For the instructor only.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="646"/>
        <source>Leave the exam? This ends it: no more marks can be made in it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="647"/>
        <source>Change of mode</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="847"/>
        <source>Instructor: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="849"/>
        <source>Guided practice: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="849"/>
        <source>Guided practice ended: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="850"/>
        <source>Exam: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="850"/>
        <source>Exam ended: case %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="864"/>
        <source>%1 nodes, %2 tetrahedra</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="906"/>
        <source>Backend: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="906"/>
        <source>Backend: %1 (fallback)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="908"/>
        <source>Simulation: %1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="909"/>
        <source>Haptic: %1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="911"/>
        <source>mouse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="912"/>
        <source>simulated HandHIRO</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="913"/>
        <source>Device: %1, %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="913"/>
        <source>connected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="913"/>
        <source>not connected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="914"/>
        <source>View: %1 fps</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::PatientPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="120"/>
        <source>Breast phantom (paper&apos;s tumour)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="121"/>
        <source>Box phantom</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="122"/>
        <source>The paper&apos;s breast with its tumour (107 kPa at x = 12.5 cm).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="123"/>
        <source>A 10 x 10 x 5 cm block of tissue, no tumour.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="130"/>
        <source>Coarse (about 1,000 nodes, real time on a CPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="131"/>
        <source>Paper (about 9,100 nodes, GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="132"/>
        <source>Fine (GPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="133"/>
        <source>Patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="134"/>
        <source>Resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="135"/>
        <source>Tissue Young&apos;s modulus</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="136"/>
        <source>Poisson ratio</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="137"/>
        <source>Load patient</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="138"/>
        <source>Import scan...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="139"/>
        <source>Patients from the library (built-in shapes, graded tumour cases, imported scans) and the built-in phantoms.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="140"/>
        <source>Phantom patients only; an imported scan keeps the resolution it was meshed at.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ProgressWindow</name>
    <message>
        <location filename="../ui/progress_window.cpp" line="83"/>
        <source>Trainee progress</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <source>Date</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <source>Case</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="194"/>
        <source>Sensitivity</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="195"/>
        <source>False positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Light</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Medium</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Deep</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <source>Deep over tumours</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <source>Exam time (s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Passed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="106"/>
        <source>Trainee:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="111"/>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Trainee</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Exams</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest sensitivity</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest false positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Latest deep coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best sensitivity</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best false positives</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="115"/>
        <source>Best deep coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="117"/>
        <source>Class</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="147"/>
        <source>No patient library is open: no trainees.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="191"/>
        <source>yes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="191"/>
        <source>no</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="196"/>
        <source>Coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="199"/>
        <source>Exam time</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ReviewWindow</name>
    <message>
        <location filename="../ui/review_window.cpp" line="215"/>
        <source>Export the session as CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="215"/>
        <source>CSV files (*.csv)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="217"/>
        <source>Export CSV</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="221"/>
        <source>Folder for the exam report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="225"/>
        <source>Save report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="226"/>
        <source>Report written to %1 (%2)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="229"/>
        <source>Folder for the PNG frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/review_window.cpp" line="232"/>
        <source>%n frame(s) written to %1</source>
        <translation>
            <numerusform>%n frame written to %1</numerusform>
            <numerusform>%n frames written to %1</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="277"/>
        <source>Review: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="278"/>
        <location filename="../ui/review_window.cpp" line="336"/>
        <source>Pause</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="278"/>
        <location filename="../ui/review_window.cpp" line="336"/>
        <location filename="../ui/review_window.cpp" line="345"/>
        <source>Play</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="279"/>
        <source>Speed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="280"/>
        <source>Export CSV...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="281"/>
        <source>Export PNG frames...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="282"/>
        <source>Instructor events and trainee marks (click to go there)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="283"/>
        <source>&lt;b&gt;Exam score&lt;/b&gt;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="284"/>
        <source>Coverage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="285"/>
        <source>The skin coloured by the highest pressure reached: grey none, yellow light, orange medium, red deep</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="286"/>
        <source>Save report...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="288"/>
        <source>Scoring the exam...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="297"/>
        <source>Force on each fingertip (N): sent to the device (solid), re-simulated simulation force (dashed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="298"/>
        <source>Force on each fingertip (N): recorded (solid), re-simulated (dashed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="302"/>
        <source>%1 (re-sim.)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="304"/>
        <source>now</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="305"/>
        <source>Events</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="366"/>
        <location filename="../ui/review_window.cpp" line="398"/>
        <source>No score: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="371"/>
        <source>Tumours found: %1 of %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="372"/>
        <source>False positives: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="373"/>
        <source>Coverage: light %1, medium %2, deep %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="375"/>
        <source>Vertical strips: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="399"/>
        <source>The exam is still being scored.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="461"/>
        <source>Re-simulation stopped: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="464"/>
        <source>Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation forces: %4 N (%5 finger at %6 s; largest recorded force %7 N).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="473"/>
        <source>Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation forces: 0 N (largest recorded force %4 N).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="480"/>
        <source>Reproduced: same backend and settings give the same forces.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="481"/>
        <source>Not reproduced exactly (another backend or settings).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="483"/>
        <source>The forces sent at 1 kHz differ from the simulation&apos;s by up to %1 N (the haptic loop&apos;s local contact model, coupling and safety filter).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="487"/>
        <source>Re-simulated %1 of %2 ticks (backend %3) from the recorded device input at the scenario&apos;s time step. Largest difference from the recorded forces: %4 N (largest recorded force %5 N).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="496"/>
        <source>The recording was interrupted: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="497"/>
        <source>The recording was recovered after an interruption.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="504"/>
        <source>Written: %1</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::ScoreDialog</name>
    <message>
        <location filename="../ui/score_dialog.cpp" line="25"/>
        <source>Exam score</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="29"/>
        <source>Tumours found:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="29"/>
        <source>%1 of %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="30"/>
        <source>False positives:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="31"/>
        <source>Sensitivity:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="32"/>
        <source>Positive predictive value:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="33"/>
        <source>Position error:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="34"/>
        <source>%1 mm (mean over the tumours found)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="35"/>
        <source>Exam time:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="35"/>
        <source>%1 s</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="36"/>
        <source>Coverage:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="37"/>
        <source>light %1, medium %2, deep %3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="39"/>
        <source>Vertical strips:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="42"/>
        <source>tumour %1: %2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="42"/>
        <source>yes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="42"/>
        <source>no</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="43"/>
        <source>Deep pressure over each tumour:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="46"/>
        <source>Advice:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="56"/>
        <source>Skin from above: grey not pressed, yellow light, orange medium, red deep; circles: the tumours (green: found); marks: green correct, red false</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="60"/>
        <source>Save report...</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="63"/>
        <source>Close</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="67"/>
        <source>Save the exam report into</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="71"/>
        <source>Save report</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::SimulationPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="337"/>
        <source>Backend</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="338"/>
        <source>CG tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="339"/>
        <source>CG max. iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="340"/>
        <source>State</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="341"/>
        <source>Safety</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="342"/>
        <source>Step time</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="343"/>
        <source>CG iterations</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="344"/>
        <source>Simulation rate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="345"/>
        <source>Haptic rate</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="346"/>
        <source>Apply solver settings</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="347"/>
        <source>A backend change takes effect when the patient is (re)loaded.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="360"/>
        <source>stopped</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="361"/>
        <source>loading</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="362"/>
        <source>running</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="363"/>
        <source>swapping</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="364"/>
        <source>error: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="369"/>
        <source>no fault</source>
        <translation type="unfinished"></translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels.cpp" line="370"/>
        <source>%n backend fallback(s)</source>
        <translation>
            <numerusform>%n backend fallback</numerusform>
            <numerusform>%n backend fallbacks</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels.cpp" line="371"/>
        <source>%n divergence reset(s)</source>
        <translation>
            <numerusform>%n divergence reset</numerusform>
            <numerusform>%n divergence resets</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="372"/>
        <source>forces held and blended</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="376"/>
        <source>%1 ms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="378"/>
        <location filename="../ui/panels.cpp" line="379"/>
        <source>%1 Hz</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourEditor</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Tumour (paper, 107 kPa)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Ueda et al., paper section 4.1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Invasive ductal carcinoma (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Krouskop et al. 1998: 93-112 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Invasive ductal carcinoma (Krouskop, 20%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Krouskop et al. 1998: 460-558 kPa at 20% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Fibrous tissue (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Krouskop et al. 1998: 96-116 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>DCIS (Krouskop, 20%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>Krouskop et al. 1998: 291-307 kPa at 20% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Fibroglandular (Krouskop, 5%)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Krouskop et al. 1998: 28-35 kPa at 5% precompression</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="19"/>
        <source>IDC high grade (Samani)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="19"/>
        <source>Samani et al. 2007: 10-43 kPa by grade, small strain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="20"/>
        <source>Fibroadenoma (Samani, 2x fat)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="20"/>
        <source>Samani et al. 2007: about 6.4 kPa</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="244"/>
        <location filename="../ui/panels.cpp" line="272"/>
        <source>Source: %1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="273"/>
        <source>Preset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="274"/>
        <source>Stiffness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="275"/>
        <source>Add by shape</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="276"/>
        <source>Sphere</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="277"/>
        <source>Ellipsoid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="278"/>
        <source>Shape</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="279"/>
        <source>Centre x, y, z</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="280"/>
        <source>Radius (x, y, z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="281"/>
        <source>Add tumour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="282"/>
        <source>Remove selected</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="283"/>
        <source>Brush</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="284"/>
        <source>Radius</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="285"/>
        <source>Depth below the skin</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="286"/>
        <source>Paint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="287"/>
        <source>Erase</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="288"/>
        <source>Drag on the breast to paint tumour tissue (one undo step per stroke)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="289"/>
        <source>Drag on the breast to restore healthy tissue</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="290"/>
        <source>Undo</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="291"/>
        <source>Redo</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>palpation::ui::VtkView</name>
    <message>
        <location filename="../ui/vtk_view.cpp" line="599"/>
        <source>no OpenGL context for a native window on this platform (%1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="602"/>
        <source>the display&apos;s OpenGL (%1) has no stereo buffers; quad-buffer stereo needs a stereo-capable GPU, driver and display</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="821"/>
        <source>Quad-buffer stereo is not available: %1. Showing anaglyph (red/cyan glasses) instead; side-by-side and interlaced are also available.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="823"/>
        <source>the view is not initialised yet</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
