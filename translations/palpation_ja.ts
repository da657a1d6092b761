<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="ja_JP">
<context>
    <name>DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="51"/>
        <source>Thumb</source>
        <translation>親指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="51"/>
        <source>Index</source>
        <translation>人差し指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="52"/>
        <source>Middle</source>
        <translation>中指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="52"/>
        <source>Ring</source>
        <translation>薬指</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="53"/>
        <source>Little</source>
        <translation>小指</translation>
    </message>
</context>
<context>
    <name>ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="26"/>
        <source>thumb</source>
        <translation>親指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="26"/>
        <source>index</source>
        <translation>人差し指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="27"/>
        <source>middle</source>
        <translation>中指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="27"/>
        <source>ring</source>
        <translation>薬指</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="28"/>
        <source>little</source>
        <translation>小指</translation>
    </message>
</context>
<context>
    <name>ReviewWindow</name>
    <message>
        <location filename="../ui/review_window.cpp" line="34"/>
        <source>thumb</source>
        <translation>親指</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="34"/>
        <source>index</source>
        <translation>人差し指</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="35"/>
        <source>middle</source>
        <translation>中指</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="35"/>
        <source>ring</source>
        <translation>薬指</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="36"/>
        <source>little</source>
        <translation>小指</translation>
    </message>
</context>
<context>
    <name>palpation::ui::DevicePanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="442"/>
        <source>Simulated HandHIRO (scripted palpation)</source>
        <translation>シミュレーションの HandHIRO（自動触診）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="443"/>
        <source>Mouse palpation (no robot)</source>
        <translation>マウス触診（ロボットなし）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="444"/>
        <source>Device</source>
        <translation>デバイス</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="445"/>
        <source>HandHIRO address</source>
        <translation>HandHIRO アドレス</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="446"/>
        <source>Loop jitter</source>
        <translation>ループのジッタ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="447"/>
        <source>The HandHIRO network link is chosen at start: palpation-trainer --device emulator, or --device handhiro --robot ADDRESS:PORT.</source>
        <translation>HandHIRO のネットワーク接続は起動時に選びます: palpation-trainer --device emulator、または --device handhiro --robot アドレス:ポート</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="460"/>
        <source>attached</source>
        <translation>装着</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="460"/>
        <source>released</source>
        <translation>解放</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="462"/>
        <source>%1 us (max over 0.5 s)</source>
        <translation>%1 µs（0.5 秒間の最大）</translation>
    </message>
</context>
<context>
    <name>palpation::ui::EventText</name>
    <message>
        <location filename="../ui/event_text.cpp" line="21"/>
        <source>Patient&apos;s tumour</source>
        <translation>患者の腫瘍</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="23"/>
        <source>%1 at (%2, %3, %4) cm, %5 kPa</source>
        <translation>%1 (%2, %3, %4) cm、%5 kPa</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="24"/>
        <source>Sphere</source>
        <translation>球</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="24"/>
        <source>Ellipsoid</source>
        <translation>楕円体</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="26"/>
        <source>Painted tumour %1, %2 kPa</source>
        <translation>描画した腫瘍 %1、%2 kPa</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="31"/>
        <source>%1 (%n elements)</source>
        <translation>
            <numerusform>%1（%n 要素）</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="36"/>
        <source>Add tumour: %1</source>
        <translation>腫瘍を追加: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="37"/>
        <source>Remove tumour: %1</source>
        <translation>腫瘍を削除: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="38"/>
        <source>Erase</source>
        <translation>消去</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="38"/>
        <source>Paint</source>
        <translation>描画</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="40"/>
        <source>Erase stroke (%n elements)</source>
        <translation>
            <numerusform>消去ストローク（%n 要素）</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/event_text.cpp" line="40"/>
        <source>Paint stroke (%n elements)</source>
        <translation>
            <numerusform>描画ストローク（%n 要素）</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="43"/>
        <source>Undo: %1</source>
        <translation>取り消し: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="48"/>
        <source>loading patient: %1</source>
        <translation>患者を読み込み中: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="50"/>
        <source>patient loaded: %1 nodes, %2 tetrahedra, backend %3</source>
        <translation>患者を読み込みました: 節点 %1、四面体 %2、バックエンド %3</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="51"/>
        <source>patient not loaded: %1</source>
        <translation>患者を読み込めませんでした: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="52"/>
        <source>solver/contact parameters changed</source>
        <translation>ソルバー／接触のパラメータを変更</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="56"/>
        <source>device: mouse palpation</source>
        <translation>デバイス: マウスで触診</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="57"/>
        <source>device: scripted hand</source>
        <translation>デバイス: 自動触診ハンド</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="58"/>
        <source>trainee mode</source>
        <translation>研修生モード</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="59"/>
        <source>instructor mode</source>
        <translation>指導者モード</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="60"/>
        <source>guided practice (trainee)</source>
        <translation>ガイド付き練習（研修生）</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="61"/>
        <source>exam (trainee)</source>
        <translation>試験（研修生）</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="65"/>
        <source>trainee mark %1 at (%2, %3, %4) cm</source>
        <translation>研修生のマーク %1（%2, %3, %4 cm）</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="68"/>
        <source>trainee mark %1</source>
        <translation>研修生のマーク %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="69"/>
        <source>, %1 % confident</source>
        <translation>、確信度 %1 %</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="70"/>
        <source>: %1</source>
        <translation>: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="73"/>
        <source>guided practice ended</source>
        <translation>ガイド付き練習を終了</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="73"/>
        <source>exam ended</source>
        <translation>試験を終了</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="74"/>
        <source>backend error: %1; continuing on the CPU from rest (forces held, then blended)</source>
        <translation>バックエンドのエラー: %1。静止状態から CPU で続行します（力を保持してから滑らかに切り替え）</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="75"/>
        <source>simulation diverged (%1): body reset to rest (forces held, then blended)</source>
        <translation>シミュレーションが発散しました（%1）: 物体を静止状態に戻しました（力を保持してから滑らかに切り替え）</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="77"/>
        <source>simulation stopped: %1</source>
        <translation>シミュレーションが停止しました: %1</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="86"/>
        <source>small</source>
        <translation>小さめ</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="87"/>
        <source>medium</source>
        <translation>中くらい</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="88"/>
        <source>large</source>
        <translation>大きめ</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="89"/>
        <source>wide and flat</source>
        <translation>広く平ら</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="90"/>
        <source>narrow and projecting</source>
        <translation>細く突出</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="93"/>
        <source>Healthy breast, %1 (%2 mL), the paper&apos;s size, no tumour</source>
        <translation>健康な乳房、%1（%2 mL、論文の大きさ）、腫瘍なし</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="94"/>
        <source>Healthy breast, %1 (%2 mL), no tumour</source>
        <translation>健康な乳房、%1（%2 mL）、腫瘍なし</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="96"/>
        <source>The paper&apos;s case: medium breast, tumour 3 cm diameter, 107 kPa, centre 2.0 cm below the skin</source>
        <translation>論文の症例: 中くらいの乳房、直径 3 cm・107 kPa の腫瘍、中心は皮膚の下 2.0 cm</translation>
    </message>
    <message>
        <source>The paper&apos;s case: medium breast, tumour 3 cm diameter, 107 kPa, 1.5 cm below the skin</source>
        <translation type="vanished">論文の症例: 中くらいの乳房、直径 3 cm・107 kPa の腫瘍、皮膚の下 1.5 cm</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>soft</source>
        <translation>柔らかい</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>hard</source>
        <translation>硬い</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="98"/>
        <source>firm</source>
        <translation>硬めの</translation>
    </message>
    <message>
        <location filename="../ui/event_text.cpp" line="99"/>
        <source>Medium breast, %1 tumour %2 cm diameter (%3 kPa), centre %4 cm below the skin</source>
        <translation>中くらいの乳房、%1腫瘍 直径 %2 cm（%3 kPa）、中心は皮膚の下 %4 cm</translation>
    </message>
</context>
<context>
    <name>palpation::ui::ForcePlots</name>
    <message>
        <location filename="../ui/force_plots.cpp" line="107"/>
        <source>Export plot as PNG</source>
        <translation>グラフを PNG で出力</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="107"/>
        <source>PNG images (*.png)</source>
        <translation>PNG 画像 (*.png)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="111"/>
        <source>Export forces as CSV</source>
        <translation>力を CSV で出力</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="111"/>
        <source>CSV files (*.csv)</source>
        <translation>CSV ファイル (*.csv)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="118"/>
        <source>|F| vs time</source>
        <translation>|F| と時間</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="119"/>
        <source>Fz vs time</source>
        <translation>Fz と時間</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="120"/>
        <source>Fz vs x (Fig. 6)</source>
        <translation>Fz と x（図 6）</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="121"/>
        <source>solid: sent to the device (limit %1 N, dotted); dashed: simulated contact force</source>
        <translation>実線: デバイスへ送った力（上限 %1 N、点線）、破線: シミュレーションの接触力</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="122"/>
        <source>Force magnitude per finger (N)</source>
        <translation>指ごとの力の大きさ (N)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="123"/>
        <source>Fz per finger (N)</source>
        <translation>指ごとの Fz (N)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="124"/>
        <source>Fz (N) against finger x (m)</source>
        <translation>指の x 位置 (m) に対する Fz (N)</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="130"/>
        <source>%1 (simulated)</source>
        <translation>%1（シミュレーション）</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="135"/>
        <location filename="../ui/force_plots.cpp" line="136"/>
        <source>device limit</source>
        <translation>デバイス上限</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="137"/>
        <source>Resume</source>
        <translation>再開</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="137"/>
        <source>Pause</source>
        <translation>一時停止</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="138"/>
        <source>Export PNG...</source>
        <translation>PNG 出力...</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="139"/>
        <source>Export CSV...</source>
        <translation>CSV 出力...</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="141"/>
        <source>The device renders the simulated force times the force scale, chosen when the patient loads: a deep press (%1 % of the tissue thickness) over the stiffest part of the patient maps to %2 % of the device&apos;s limit, so that the tumour&apos;s extra force stays within the device&apos;s range. Device limit %3 N = %4 N simulated. Solid lines: sent (device units); dashed: simulated.</source>
        <translation>デバイスはシミュレーションの力に力のスケールを掛けて出力します。スケールは患者の読み込み時に決まります: 患者の最も硬い部分の上での深い押し込み（組織の厚さの %1 %）がデバイス上限の %2 % になるように選ぶので、腫瘍による余分な力もデバイスの範囲に収まります。デバイス上限 %3 N = シミュレーション %4 N。実線: 送った力（デバイスの単位）、破線: シミュレーション。</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="157"/>
        <source>Force scale %1 (device configuration): %2 N simulated -&gt; %3 N at the device</source>
        <translation>力のスケール %1（デバイス設定）: シミュレーション %2 N → デバイス %3 N</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="162"/>
        <source>Force scale %1: deep press %2 N simulated -&gt; %3 N at the device (limit %4 N)</source>
        <translation>力のスケール %1: 深い押し込み シミュレーション %2 N → デバイス %3 N（上限 %4 N）</translation>
    </message>
    <message>
        <location filename="../ui/force_plots.cpp" line="167"/>
        <source>Force scale 1: simulated forces sent unscaled</source>
        <translation>力のスケール 1: シミュレーションの力をそのまま送ります</translation>
    </message>
</context>
<context>
    <name>palpation::ui::ImportDialog</name>
    <message>
        <location filename="../ui/import_dialog.cpp" line="98"/>
        <source>Scanned breast surface</source>
        <translation>スキャンした乳房表面</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="99"/>
        <source>Surface meshes (*.stl *.obj *.ply);;All files (*)</source>
        <translation>表面メッシュ (*.stl *.obj *.ply);;すべてのファイル (*)</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="109"/>
        <source>Cancelling...</source>
        <translation>中止しています...</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="124"/>
        <source>Import a scanned breast</source>
        <translation>スキャンした乳房の取り込み</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="130"/>
        <source>Patient name</source>
        <translation>患者名</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="131"/>
        <source>Resolution</source>
        <translation>解像度</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="132"/>
        <source>File units</source>
        <translation>ファイルの単位</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="133"/>
        <source>Chest-wall plane</source>
        <translation>胸壁平面</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="137"/>
        <source>Scan file</source>
        <translation>スキャンファイル</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="138"/>
        <source>n (into the chest), d (m)</source>
        <translation>n（胸の内側向き）、d (m)</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="143"/>
        <source>Browse...</source>
        <translation>参照...</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="144"/>
        <source>Coarse (real time on a CPU)</source>
        <translation>粗い（CPU でリアルタイム）</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="145"/>
        <source>Paper (GPU)</source>
        <translation>論文（GPU）</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="146"/>
        <source>Fine (GPU)</source>
        <translation>細かい（GPU）</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="147"/>
        <source>metres</source>
        <translation>メートル</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="148"/>
        <source>centimetres</source>
        <translation>センチメートル</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="149"/>
        <source>millimetres</source>
        <translation>ミリメートル</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="150"/>
        <source>Find automatically (the largest flat region)</source>
        <translation>自動で検出（最も広い平坦な領域）</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="151"/>
        <source>Untick to give the plane n . x = d by hand: n points out of the body into the chest.</source>
        <translation>チェックを外すと平面 n . x = d を手で指定できます。n は乳房から胸の内側へ向く法線です。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="152"/>
        <source>Import</source>
        <translation>取り込み</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="153"/>
        <source>Cancel import</source>
        <translation>取り込みを中止</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="154"/>
        <source>Save as patient</source>
        <translation>患者として保存</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="155"/>
        <source>Close</source>
        <translation>閉じる</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="181"/>
        <source>Choose a scan file (STL, OBJ or PLY) first.</source>
        <translation>先にスキャンファイル（STL、OBJ、PLY）を選んでください。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="190"/>
        <source>The base plane&apos;s normal must not be zero.</source>
        <translation>胸壁平面の法線をゼロにすることはできません。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="205"/>
        <source>Reading %1...</source>
        <translation>%1 を読み込んでいます...</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="220"/>
        <source>Cancelled: nothing was saved.</source>
        <translation>中止しました。何も保存されていません。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="226"/>
        <source>Import failed: nothing was saved.</source>
        <translation>取り込みに失敗しました。何も保存されていません。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="231"/>
        <source>Done in %1 s (meshing %2 s).</source>
        <translation>完了: %1 秒（メッシュ生成 %2 秒）。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="235"/>
        <source>%1 nodes, %2 tetrahedra. Repairs: %3. Chest wall (fixed) %4: n = (%5, %6, %7), %8 cm², %9 % of the body&apos;s outline, tilted %10° from the scan&apos;s z axis.</source>
        <translation>節点 %1、四面体 %2。修復: %3。胸壁（固定）%4: n = (%5, %6, %7)、%8 cm²、体の輪郭の %9 %、スキャンの z 軸から %10° 傾斜。</translation>
    </message>
    <message>
        <source>%1 nodes, %2 tetrahedra. Repairs: %3. Base plane %4: n = (%5, %6, %7), %8 cm².</source>
        <translation type="vanished">節点 %1、四面体 %2。修復: %3。胸壁平面（%4）: n = (%5, %6, %7)、%8 cm²。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="239"/>
        <source>none</source>
        <translation>なし</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="240"/>
        <source>found</source>
        <translation>自動検出</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="240"/>
        <source>given</source>
        <translation>手動指定</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="251"/>
        <source>No patient library is open.</source>
        <translation>患者ライブラリが開かれていません。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="259"/>
        <source>Give the patient a name.</source>
        <translation>患者名を入力してください。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="264"/>
        <source>A patient named &quot;%1&quot; exists already in %2: choose another name.</source>
        <translation>患者「%1」は %2 にすでにあります。別の名前を選んでください。</translation>
    </message>
    <message>
        <location filename="../ui/import_dialog.cpp" line="275"/>
        <source>Saved as &quot;%1&quot; in the patient library.</source>
        <translation>患者ライブラリに「%1」として保存しました。</translation>
    </message>
</context>
<context>
    <name>palpation::ui::MainWindow</name>
    <message>
        <location filename="../ui/main_window.cpp" line="160"/>
        <source>Mouse palpation: move over the breast; the wheel or a downward drag presses the fingertip in.</source>
        <translation>マウス触診: 乳房の上で動かします。ホイールまたは下向きのドラッグで指先を押し込みます。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="170"/>
        <source>No element lies inside that shape: nothing added.</source>
        <translation>その形状の中に要素がありません。追加されませんでした。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="220"/>
        <source>Stored pressure levels not used (defaults apply): %1</source>
        <translation>保存された圧の段階は使われません（既定値を使用）: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="260"/>
        <source>This session is not recorded: %1</source>
        <translation>このセッションは記録されていません: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="262"/>
        <source>Recovered interrupted recordings: %1</source>
        <translation>中断された記録を復元しました: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="264"/>
        <source>Patient library not available (built-in phantoms only): %1</source>
        <translation>患者ライブラリを使えません（内蔵ファントムのみ）: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="304"/>
        <source>no patient library is open: %1</source>
        <translation>患者ライブラリが開かれていません: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="340"/>
        <source>No fingertip on the breast: nothing marked.</source>
        <translation>乳房に触れている指先がありません。マークしませんでした。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="340"/>
        <source>This session is not recorded: nothing marked.</source>
        <translation>このセッションは記録されていません。マークしませんでした。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="382"/>
        <source>Patient &quot;%1&quot; saved; choose it and Load patient to palpate it.</source>
        <translation>患者「%1」を保存しました。選んで「患者を読み込む」を押すと触診できます。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="395"/>
        <source>Open a session recording</source>
        <translation>セッションの記録を開く</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="396"/>
        <source>Session recordings (*.palrec *.prec);;All files (*)</source>
        <translation>セッションの記録 (*.palrec *.prec);;すべてのファイル (*)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="399"/>
        <source>Cannot open the recording</source>
        <translation>記録を開けません</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="403"/>
        <source>Save screenshot</source>
        <translation>スクリーンショットを保存</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="403"/>
        <source>PNG images (*.png)</source>
        <translation>PNG 画像 (*.png)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="433"/>
        <location filename="../ui/main_window.cpp" line="620"/>
        <source>Stereo</source>
        <translation>立体視</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="443"/>
        <source>Eye separation</source>
        <translation>眼間距離</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="443"/>
        <source>Eye angle (degrees):</source>
        <translation>視差角（度）:</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="522"/>
        <source>End the exam now? No more marks can be made after it.</source>
        <translation>試験を今終了しますか？終了後はマークできません。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="541"/>
        <location filename="../ui/main_window.cpp" line="550"/>
        <location filename="../ui/main_window.cpp" line="555"/>
        <location filename="../ui/main_window.cpp" line="650"/>
        <source>Curriculum</source>
        <translation>カリキュラム</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="547"/>
        <source>Open a curriculum</source>
        <translation>カリキュラムを開く</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="547"/>
        <source>Curricula (*.json)</source>
        <translation>カリキュラム (*.json)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="606"/>
        <source>Palpation Trainer</source>
        <translation>触診トレーナー</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="607"/>
        <source>&amp;File</source>
        <translation>ファイル(&amp;F)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="608"/>
        <source>&amp;Open recording...</source>
        <translation>記録を開く(&amp;O)...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="609"/>
        <source>Mark lump here (M)</source>
        <translation>しこりをマーク (M)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="610"/>
        <source>Trainee: &quot;I feel a lump here&quot;: marks the index fingertip&apos;s position in the recording</source>
        <translation>研修生:「ここにしこりがある」― 人差し指の指先の位置を記録にマークします</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="611"/>
        <source>Save &amp;screenshot...</source>
        <translation>スクリーンショットを保存(&amp;S)...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="612"/>
        <source>&amp;Quit</source>
        <translation>終了(&amp;Q)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="613"/>
        <source>&amp;Edit</source>
        <translation>編集(&amp;E)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="614"/>
        <source>Undo</source>
        <translation>元に戻す</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="615"/>
        <source>Redo</source>
        <translation>やり直し</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="616"/>
        <source>&amp;View</source>
        <translation>表示(&amp;V)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="617"/>
        <source>Camera</source>
        <translation>カメラ</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Oblique</source>
        <translation>斜め</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Top</source>
        <translation>上</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Side</source>
        <translation>側面</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="618"/>
        <source>Front</source>
        <translation>正面</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Mono</source>
        <translation>モノ</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Anaglyph (red/cyan)</source>
        <translation>アナグリフ（赤/シアン）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Side by side</source>
        <translation>サイドバイサイド</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Interlaced</source>
        <translation>インターレース</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="621"/>
        <source>Quad-buffer (shutter glasses)</source>
        <translation>クアッドバッファ（シャッターメガネ）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="623"/>
        <source>Eye separation...</source>
        <translation>眼間距離...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="624"/>
        <source>Mirrored (half-mirror display)</source>
        <translation>鏡像（ハーフミラー表示）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="625"/>
        <source>Fast rendering (software OpenGL)</source>
        <translation>高速描画（ソフトウェア OpenGL）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="626"/>
        <source>A lighter 3-D view: plain background, no highlights on the skin, an unlit chest. On by itself when the computer draws OpenGL in software.</source>
        <translation>軽い 3D 表示：単色の背景、皮膚のハイライトなし、陰影なしの胸壁。コンピューターが OpenGL をソフトウェアで描画するときは自動でオンになります。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="628"/>
        <source>Displacement colour map</source>
        <translation>変位カラーマップ</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="629"/>
        <source>Stress colour map (von Mises)</source>
        <translation>応力カラーマップ（ミーゼス）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="630"/>
        <source>Show tumours</source>
        <translation>腫瘍を表示</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="631"/>
        <source>Panels</source>
        <translation>パネル</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="632"/>
        <source>&amp;Mode</source>
        <translation>モード(&amp;M)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="633"/>
        <source>Instructor mode</source>
        <translation>指導者モード</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="642"/>
        <source>Coverage overlay</source>
        <translation>触診範囲の表示</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="643"/>
        <source>Colours the skin by the highest pressure reached: yellow light, orange medium, red deep. Not shown in an exam.</source>
        <translation>皮膚を到達した最大の圧で色分けします：黄は軽い圧、橙は中程度の圧、赤は深い圧。試験中は表示しません。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="645"/>
        <source>Clear coverage</source>
        <translation>触診範囲を消去</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="646"/>
        <source>Trainee progress...</source>
        <translation>研修生の進捗...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="647"/>
        <source>Each trainee&apos;s exams over time and the class&apos;s results</source>
        <translation>各研修生の試験の推移とクラスの成績</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="648"/>
        <source>Pressure levels...</source>
        <translation>圧の段階...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="649"/>
        <source>What counts as light, medium and deep pressure in the coverage and the score</source>
        <translation>触診範囲と採点で軽い圧・中程度・深い圧とみなす基準</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="651"/>
        <source>Open curriculum file...</source>
        <translation>カリキュラムファイルを開く...</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="652"/>
        <source>No curriculum (free exams)</source>
        <translation>カリキュラムなし（自由試験）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="653"/>
        <source>Next curriculum case</source>
        <translation>カリキュラムの次の症例</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="654"/>
        <source>Loads the trainee&apos;s first case of the curriculum not yet passed</source>
        <translation>研修生がまだ合格していないカリキュラムの最初の症例を読み込みます</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="658"/>
        <source>Tools</source>
        <translation>ツール</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="659"/>
        <source>Coverage</source>
        <translation>触診範囲</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="660"/>
        <source>Camera / scripted hand</source>
        <translation>カメラ / 自動触診ハンド</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="661"/>
        <source>Palpate with the mouse</source>
        <translation>マウスで触診</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="735"/>
        <source>Trainee</source>
        <translation>研修生</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="736"/>
        <source>Who is the trainee? Choose a name or type a new one (empty: anonymous, no result stored).</source>
        <translation>研修生は誰ですか？名前を選ぶか新しい名前を入力してください（空欄：匿名、結果は保存されません）。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="754"/>
        <source>Trainee not added to the library: %1</source>
        <translation>研修生をライブラリに追加できませんでした：%1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="765"/>
        <source>Patient library not available: %1</source>
        <translation>患者ライブラリを使用できません：%1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="802"/>
        <source>The exam&apos;s result is kept on this station: %1</source>
        <translation>試験結果はこの端末に保管されています: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="805"/>
        <source>The exam&apos;s result is not stored: %1</source>
        <translation>試験の結果は保存されていません：%1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="837"/>
        <source>Pressure levels set: they apply to the exams that start from now on.</source>
        <translation>圧の段階を設定しました: これから始まる試験に適用されます。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="869"/>
        <source>No curriculum is chosen (Mode &gt; Curriculum).</source>
        <translation>カリキュラムが選ばれていません（モード &gt; カリキュラム）。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="877"/>
        <source>The trainee&apos;s results could not be read: %1</source>
        <translation>研修生の結果を読み込めませんでした: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="882"/>
        <source>%1 has passed every case of %2.</source>
        <translation>%1 は %2 のすべての症例に合格しました。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="923"/>
        <source>Curriculum %1: case %2 of %3</source>
        <translation>カリキュラム %1: 症例 %2 / %3</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="924"/>
        <source>Curriculum %1</source>
        <translation>カリキュラム %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="942"/>
        <source>Coverage: %1 none %2 light %3 %4 medium %5 %6 deep %7</source>
        <translation>触診範囲：%1 なし %2 軽い圧 %3 %4 中程度 %5 %6 深い圧 %7</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1030"/>
        <source>, trainee %1</source>
        <translation>、研修生 %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1105"/>
        <source>Not recording</source>
        <translation>記録していません</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1106"/>
        <source>Recording stopped: %1</source>
        <translation>記録が停止しました: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1107"/>
        <source>Recording (%1 marks)</source>
        <translation>記録中（マーク %1 件）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="144"/>
        <location filename="../ui/main_window.cpp" line="662"/>
        <source>Patient</source>
        <translation>患者</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="334"/>
        <source>The exam has ended: nothing marked.</source>
        <translation>試験は終了しています。マークしませんでした。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="349"/>
        <source>Mark %1: &quot;I feel a lump here&quot; at (%2, %3, %4) cm, %5 % confident, recorded.</source>
        <translation>マーク %1:「ここにしこりがある」(%2, %3, %4) cm、確信度 %5 % を記録しました。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="634"/>
        <source>The instructor&apos;s view: every panel, the answer included. From a trainee mode it asks for a confirmation.</source>
        <translation>指導者の表示: 答えを含むすべてのパネル。研修生のモードから戻るときは確認を求めます。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="636"/>
        <source>Guided practice</source>
        <translation>ガイド付き練習</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="637"/>
        <source>Trainee: palpate and mark; the instructor&apos;s panels are hidden.</source>
        <translation>研修生: 触診してマークします。指導者のパネルは表示されません。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="638"/>
        <source>Exam</source>
        <translation>試験</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="639"/>
        <source>Trainee examined: palpate and mark; the answer stays hidden until the exam ends.</source>
        <translation>研修生の試験: 触診してマークします。試験が終わるまで答えは表示されません。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="640"/>
        <source>End exam</source>
        <translation>試験を終了</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="641"/>
        <source>Stops the exam: no more marks.</source>
        <translation>試験を終了します。以後はマークできません。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Possible (25 %)</source>
        <translation>可能性あり (25 %)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Likely (50 %)</source>
        <translation>たぶん (50 %)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Probable (75 %)</source>
        <translation>おそらく (75 %)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="655"/>
        <source>Certain (100 %)</source>
        <translation>確実 (100 %)</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="657"/>
        <source>How sure you are of the next mark</source>
        <translation>次のマークの確信度</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="663"/>
        <source>Tumours</source>
        <translation>腫瘍</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="664"/>
        <source>Forces</source>
        <translation>力</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="665"/>
        <source>Simulation</source>
        <translation>シミュレーション</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="666"/>
        <source>Device</source>
        <translation>デバイス</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="705"/>
        <source>Return to instructor mode? This ends the trainee&apos;s session and shows the answer, the patient&apos;s details and every panel. For the instructor only.</source>
        <translation>指導者モードに戻りますか？研修生のセッションを終了し、答え、患者の詳細、すべてのパネルを表示します。指導者専用の操作です。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="707"/>
        <source>Leave the exam? This ends it: no more marks can be made in it.</source>
        <translation>試験を抜けますか？試験は終了し、この試験ではもうマークできません。</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="708"/>
        <source>Change of mode</source>
        <translation>モードの切り替え</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1032"/>
        <source>Instructor: %1</source>
        <translation>指導者: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1034"/>
        <source>Guided practice: case %1</source>
        <translation>ガイド付き練習: 症例 %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1034"/>
        <source>Guided practice ended: case %1</source>
        <translation>ガイド付き練習終了: 症例 %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1035"/>
        <source>Exam: case %1</source>
        <translation>試験: 症例 %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1035"/>
        <source>Exam ended: case %1</source>
        <translation>試験終了: 症例 %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1049"/>
        <source>%1 nodes, %2 tetrahedra</source>
        <translation>節点 %1、四面体 %2</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1095"/>
        <source>Backend: %1</source>
        <translation>バックエンド: %1</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1095"/>
        <source>Backend: %1 (fallback)</source>
        <translation>バックエンド: %1（フォールバック）</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1097"/>
        <source>Simulation: %1 Hz</source>
        <translation>シミュレーション: %1 Hz</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1098"/>
        <source>Haptic: %1 Hz</source>
        <translation>力覚: %1 Hz</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1100"/>
        <source>mouse</source>
        <translation>マウス</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1101"/>
        <source>simulated HandHIRO</source>
        <translation>シミュレーションの HandHIRO</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1102"/>
        <source>Device: %1, %2</source>
        <translation>デバイス: %1、%2</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1102"/>
        <source>connected</source>
        <translation>接続中</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1102"/>
        <source>not connected</source>
        <translation>未接続</translation>
    </message>
    <message>
        <location filename="../ui/main_window.cpp" line="1103"/>
        <source>View: %1 fps</source>
        <translation>表示: %1 fps</translation>
    </message>
</context>
<context>
    <name>palpation::ui::PatientPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="123"/>
        <source>Breast phantom (paper&apos;s tumour)</source>
        <translation>乳房ファントム（論文の腫瘍）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="124"/>
        <source>Box phantom</source>
        <translation>直方体ファントム</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="125"/>
        <source>The paper&apos;s breast with its tumour (107 kPa at x = 12.5 cm).</source>
        <translation>論文の乳房と腫瘍（x = 12.5 cm、107 kPa）。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="126"/>
        <source>A 10 x 10 x 5 cm block of tissue, no tumour.</source>
        <translation>10 x 10 x 5 cm の組織ブロック、腫瘍なし。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="133"/>
        <source>Coarse (about 1,000 nodes, real time on a CPU)</source>
        <translation>粗い（約 1,000 節点、CPU でリアルタイム）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="134"/>
        <source>Paper (about 9,100 nodes, GPU)</source>
        <translation>論文（約 9,100 節点、GPU）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="135"/>
        <source>Fine (GPU)</source>
        <translation>細かい（GPU）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="136"/>
        <source>Patient</source>
        <translation>患者</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="137"/>
        <source>Resolution</source>
        <translation>解像度</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="138"/>
        <source>Tissue Young&apos;s modulus</source>
        <translation>組織のヤング率</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="139"/>
        <source>Poisson ratio</source>
        <translation>ポアソン比</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="140"/>
        <source>Load patient</source>
        <translation>患者を読み込む</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="141"/>
        <source>Import scan...</source>
        <translation>スキャンを取り込む...</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="142"/>
        <source>Patients from the library (built-in shapes, graded tumour cases, imported scans) and the built-in phantoms.</source>
        <translation>ライブラリの患者（内蔵の乳房形状、大きさ・深さ・硬さ別の腫瘍症例、取り込んだスキャン）と内蔵ファントム。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="143"/>
        <source>Phantom patients only; an imported scan keeps the resolution it was meshed at.</source>
        <translation>ファントム患者のみ。取り込んだスキャンはメッシュ生成時の解像度のままです。</translation>
    </message>
</context>
<context>
    <name>palpation::ui::PressureDialog</name>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="16"/>
        <source>Pressure levels</source>
        <translation>圧の段階</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="17"/>
        <source>A touch counts at a level when the fingertip pad presses the skin in by this share of the tissue&apos;s thickness under it, or presses with this force, whichever comes first. They apply to the exams that start from now on.</source>
        <translation>指先の腹が皮膚をその下の組織の厚さのこの割合だけ押し込むか、この力で押したとき（先に達した方）、その段階の触診とみなします。これから始まる試験に適用されます。</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="22"/>
        <source>Indentation (% of thickness)</source>
        <translation>押し込み（厚さの %）</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="23"/>
        <source>Force (N)</source>
        <translation>力 (N)</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="24"/>
        <source>Light</source>
        <translation>軽い圧</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="24"/>
        <source>Medium</source>
        <translation>中程度</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="24"/>
        <source>Deep</source>
        <translation>深い圧</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="46"/>
        <source>OK</source>
        <translation>OK</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="47"/>
        <source>Cancel</source>
        <translation>キャンセル</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="48"/>
        <source>Restore defaults</source>
        <translation>既定値に戻す</translation>
    </message>
    <message>
        <location filename="../ui/pressure_dialog.cpp" line="86"/>
        <source>Each level must be above the one before it, in indentation and in force, and deep indentation below 100 %.</source>
        <translation>各段階は押し込みでも力でも一つ前の段階より大きく、深い圧の押し込みは 100 % 未満でなければなりません。</translation>
    </message>
</context>
<context>
    <name>palpation::ui::ProgressWindow</name>
    <message>
        <location filename="../ui/progress_window.cpp" line="83"/>
        <source>Trainee progress</source>
        <translation>研修生の進捗</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <source>Date</source>
        <translation>日時</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <source>Case</source>
        <translation>症例</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="194"/>
        <source>Sensitivity</source>
        <translation>感度</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="195"/>
        <source>False positives</source>
        <translation>偽陽性</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Light</source>
        <translation>軽い圧</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Medium</source>
        <translation>中程度</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="89"/>
        <location filename="../ui/progress_window.cpp" line="197"/>
        <source>Deep</source>
        <translation>深い圧</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <source>Deep over tumours</source>
        <translation>腫瘍上の深い圧</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <source>Exam time (s)</source>
        <translation>試験時間（秒）</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="90"/>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Passed</source>
        <translation>合格</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="106"/>
        <source>Trainee:</source>
        <translation>研修生：</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="111"/>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Trainee</source>
        <translation>研修生</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Exams</source>
        <translation>試験数</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest</source>
        <translation>最新</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest sensitivity</source>
        <translation>最新の感度</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="113"/>
        <source>Latest false positives</source>
        <translation>最新の偽陽性</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Latest deep coverage</source>
        <translation>最新の深い圧の範囲</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best</source>
        <translation>最良</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best sensitivity</source>
        <translation>最良の感度</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="114"/>
        <source>Best false positives</source>
        <translation>最良の偽陽性</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="115"/>
        <source>Best deep coverage</source>
        <translation>最良の深い圧の範囲</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="117"/>
        <source>Class</source>
        <translation>クラス</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="147"/>
        <source>No patient library is open: no trainees.</source>
        <translation>患者ライブラリが開かれていません：研修生はいません。</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="191"/>
        <source>yes</source>
        <translation>はい</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="191"/>
        <source>no</source>
        <translation>いいえ</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="196"/>
        <source>Coverage</source>
        <translation>触診範囲</translation>
    </message>
    <message>
        <location filename="../ui/progress_window.cpp" line="199"/>
        <source>Exam time</source>
        <translation>試験時間</translation>
    </message>
</context>
<context>
    <name>palpation::ui::ReviewWindow</name>
    <message>
        <location filename="../ui/review_window.cpp" line="220"/>
        <source>Export the session as CSV</source>
        <translation>セッションを CSV で出力</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="220"/>
        <source>CSV files (*.csv)</source>
        <translation>CSV ファイル (*.csv)</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="222"/>
        <source>Export CSV</source>
        <translation>CSV 出力</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="226"/>
        <source>Folder for the exam report</source>
        <translation>試験の報告書の保存先フォルダ</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="230"/>
        <source>Save report</source>
        <translation>報告書を保存</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="231"/>
        <source>Report written to %1 (%2)</source>
        <translation>報告書を %1 に書き出しました（%2）</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="234"/>
        <source>Folder for the PNG frames</source>
        <translation>PNG フレームの保存先フォルダ</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/review_window.cpp" line="237"/>
        <source>%n frame(s) written to %1</source>
        <translation>
            <numerusform>%1 に %n フレームを書き出しました</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="280"/>
        <source>Review: %1</source>
        <translation>レビュー: %1</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="281"/>
        <location filename="../ui/review_window.cpp" line="339"/>
        <source>Pause</source>
        <translation>一時停止</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="281"/>
        <location filename="../ui/review_window.cpp" line="339"/>
        <location filename="../ui/review_window.cpp" line="348"/>
        <source>Play</source>
        <translation>再生</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="282"/>
        <source>Speed</source>
        <translation>速度</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="283"/>
        <source>Export CSV...</source>
        <translation>CSV 出力...</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="284"/>
        <source>Export PNG frames...</source>
        <translation>PNG フレーム出力...</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="285"/>
        <source>Instructor events and trainee marks (click to go there)</source>
        <translation>指導者のイベントと研修生のマーク（クリックでその時刻へ移動）</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="286"/>
        <source>&lt;b&gt;Exam score&lt;/b&gt;</source>
        <translation>&lt;b&gt;試験の成績&lt;/b&gt;</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="287"/>
        <source>Coverage</source>
        <translation>触診範囲</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="288"/>
        <source>The skin coloured by the highest pressure reached: grey none, yellow light, orange medium, red deep</source>
        <translation>到達した最大の圧で色分けした皮膚：灰色はなし、黄は軽い圧、橙は中程度、赤は深い圧</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="289"/>
        <source>Save report...</source>
        <translation>報告書を保存...</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="291"/>
        <source>Scoring the exam...</source>
        <translation>試験を採点しています...</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="300"/>
        <source>Force on each fingertip (N): sent to the device (solid), re-simulated simulation force (dashed)</source>
        <translation>各指先の力 (N): デバイスへ送った力（実線）、再シミュレーションの力（破線）</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="301"/>
        <source>Force on each fingertip (N): recorded (solid), re-simulated (dashed)</source>
        <translation>各指先の力 (N): 記録（実線）、再シミュレーション（破線）</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="305"/>
        <source>%1 (re-sim.)</source>
        <translation>%1（再計算）</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="307"/>
        <source>now</source>
        <translation>現在</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="308"/>
        <source>Events</source>
        <translation>イベント</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="369"/>
        <location filename="../ui/review_window.cpp" line="408"/>
        <source>No score: %1</source>
        <translation>成績なし：%1</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="374"/>
        <source>Tumours found: %1 of %2</source>
        <translation>発見した腫瘍：%2 個中 %1 個</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="375"/>
        <source>False positives: %1</source>
        <translation>偽陽性：%1</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="376"/>
        <source>Coverage: light %1, medium %2, deep %3</source>
        <translation>触診範囲：軽い圧 %1、中程度 %2、深い圧 %3</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="398"/>
        <source>Coverage up to %1: light %2, medium %3, deep %4</source>
        <translation>%1 までの触診範囲：軽い圧 %2、中程度 %3、深い圧 %4</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="378"/>
        <source>Vertical strips: %1</source>
        <translation>縦方向の帯：%1</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="409"/>
        <source>The exam is still being scored.</source>
        <translation>試験はまだ採点中です。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="472"/>
        <source>Re-simulation stopped: %1</source>
        <translation>再シミュレーションが停止しました: %1</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="475"/>
        <source>Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation forces: %4 N (%5 finger at %6 s; largest recorded force %7 N).</source>
        <translation>シミュレーション %2 ステップ中 %1 ステップを再シミュレーションしました（バックエンド %3）。記録されたシミュレーションの力との最大差: %4 N（%6 秒の%5、記録された最大の力 %7 N）。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="484"/>
        <source>Re-simulated %1 of %2 simulation steps (backend %3). Largest difference from the recorded simulation forces: 0 N (largest recorded force %4 N).</source>
        <translation>シミュレーション %2 ステップ中 %1 ステップを再シミュレーションしました（バックエンド %3）。記録されたシミュレーションの力との最大差: 0 N（記録された最大の力 %4 N）。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="491"/>
        <source>Reproduced: same backend and settings give the same forces.</source>
        <translation>再現しました: 同じバックエンドと設定で同じ力になります。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="492"/>
        <source>Not reproduced exactly (another backend or settings).</source>
        <translation>完全には再現されていません（バックエンドまたは設定が異なります）。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="494"/>
        <source>The forces sent at 1 kHz differ from the simulation&apos;s by up to %1 N (the haptic loop&apos;s local contact model, coupling and safety filter).</source>
        <translation>1 kHz で送った力はシミュレーションの力と最大 %1 N 異なります（力覚ループの局所接触モデル、カップリング、安全フィルタによる）。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="498"/>
        <source>Re-simulated %1 of %2 ticks (backend %3) from the recorded device input at the scenario&apos;s time step. Largest difference from the recorded forces: %4 N (largest recorded force %5 N).</source>
        <translation>記録されたデバイス入力から、シナリオの時間刻みで %2 ティック中 %1 ティックを再シミュレーションしました（バックエンド %3）。記録された力との最大差: %4 N（記録された最大の力 %5 N）。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="507"/>
        <source>The recording was interrupted: %1</source>
        <translation>記録は途中で中断されています: %1</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="508"/>
        <source>The recording was recovered after an interruption.</source>
        <translation>この記録は中断の後に復元されたものです。</translation>
    </message>
    <message>
        <location filename="../ui/review_window.cpp" line="515"/>
        <source>Written: %1</source>
        <translation>書き出しました: %1</translation>
    </message>
</context>
<context>
    <name>palpation::ui::ScoreDialog</name>
    <message>
        <location filename="../ui/score_dialog.cpp" line="65"/>
        <source>Exam score</source>
        <translation>試験の成績</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="79"/>
        <source>Tumours found:</source>
        <translation>発見した腫瘍：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="79"/>
        <source>%1 of %2</source>
        <translation>%2 個中 %1 個</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="80"/>
        <source>False positives:</source>
        <translation>偽陽性：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="81"/>
        <source>Sensitivity:</source>
        <translation>感度：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="82"/>
        <source>Positive predictive value:</source>
        <translation>陽性適中率：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="83"/>
        <source>Position error:</source>
        <translation>位置の誤差：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="84"/>
        <source>%1 mm (mean over the tumours found)</source>
        <translation>%1 mm（発見した腫瘍の平均）</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="85"/>
        <source>Exam time:</source>
        <translation>試験時間：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="85"/>
        <source>%1 s</source>
        <translation>%1 秒</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="86"/>
        <source>Coverage:</source>
        <translation>触診範囲：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="87"/>
        <source>light %1, medium %2, deep %3</source>
        <translation>軽い圧 %1、中程度 %2、深い圧 %3</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="89"/>
        <source>Vertical strips:</source>
        <translation>縦方向の帯：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="92"/>
        <source>tumour %1: %2</source>
        <translation>腫瘍 %1：%2</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="92"/>
        <source>yes</source>
        <translation>はい</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="92"/>
        <source>no</source>
        <translation>いいえ</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="93"/>
        <source>Deep pressure over each tumour:</source>
        <translation>各腫瘍上の深い圧：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="96"/>
        <source>Advice:</source>
        <translation>助言：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="29"/>
        <source>Cover the whole breast at light pressure: %1% of the skin was reached at that level.</source>
        <translation>乳房全体を軽い圧で触診してください：その圧に達した皮膚は %1% でした。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="30"/>
        <source>Cover the whole breast at medium pressure: %1% of the skin was reached at that level.</source>
        <translation>乳房全体を中程度の圧で触診してください：その圧に達した皮膚は %1% でした。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="31"/>
        <source>Cover the whole breast at deep pressure: %1% of the skin was reached at that level.</source>
        <translation>乳房全体を深い圧で触診してください：その圧に達した皮膚は %1% でした。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="36"/>
        <source>Search in vertical strips, head to foot, overlapping each by about a third of a finger pad: %1 strips covered %2% of the path.</source>
        <translation>頭側から足側へ縦方向の帯に沿って、指腹の約 3 分の 1 ずつ重ねながら探してください：%1 本の帯が経路の %2% を占めました。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="40"/>
        <source>Overlap neighbouring strips: they left gaps between them.</source>
        <translation>隣り合う帯を重ねてください：帯の間に隙間が残りました。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="42"/>
        <source>Press deep at every spot: a lump %1 mm below the skin was missed where deep pressure was not reached.</source>
        <translation>どの場所でも深い圧で押してください：深い圧が届かなかった所で、皮膚の下 %1 mm のしこりを見逃しました。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="44"/>
        <source>Check a suspected lump at all three pressure levels before marking it: %1 mark(s) found no lump.</source>
        <translation>マークする前に、疑わしいしこりを 3 段階すべての圧で確かめてください：%1 個のマークはしこりに当たりませんでした。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="45"/>
        <source>A complete examination: keep this pattern and pressure.</source>
        <translation>漏れのない診察でした：このパターンと圧を続けてください。</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="51"/>
        <source>tumours found</source>
        <translation>発見した腫瘍</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="52"/>
        <source>false positives</source>
        <translation>偽陽性</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="53"/>
        <source>light coverage</source>
        <translation>軽い圧の触診範囲</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="54"/>
        <source>medium coverage</source>
        <translation>中程度の圧の触診範囲</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="55"/>
        <source>deep coverage</source>
        <translation>深い圧の触診範囲</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="56"/>
        <source>deep pressure over each tumour</source>
        <translation>各腫瘍上での深い圧</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="57"/>
        <source>exam time</source>
        <translation>試験時間</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="72"/>
        <source>Curriculum case:</source>
        <translation>カリキュラムの症例：</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="73"/>
        <source>passed</source>
        <translation>合格</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="73"/>
        <source>not passed: %1</source>
        <translation>不合格: %1</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="106"/>
        <source>Skin from above: grey not pressed, yellow light, orange medium, red deep; circles: the tumours (green: found); marks: green correct, red false</source>
        <translation>上から見た皮膚：灰色は未触診、黄は軽い圧、橙は中程度、赤は深い圧。円：腫瘍（緑：発見）。マーク：緑は正しい、赤は誤り</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="110"/>
        <source>Save report...</source>
        <translation>報告書を保存...</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="113"/>
        <source>Close</source>
        <translation>閉じる</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="117"/>
        <source>Save the exam report into</source>
        <translation>試験の報告書の保存先</translation>
    </message>
    <message>
        <location filename="../ui/score_dialog.cpp" line="121"/>
        <source>Save report</source>
        <translation>報告書を保存</translation>
    </message>
</context>
<context>
    <name>palpation::ui::SimulationPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="350"/>
        <source>Backend</source>
        <translation>バックエンド</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="351"/>
        <source>CG tolerance</source>
        <translation>CG 許容誤差</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="352"/>
        <source>CG max. iterations</source>
        <translation>CG 最大反復回数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="353"/>
        <source>Force error held</source>
        <translation>保持する力の誤差</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="354"/>
        <source>off: fixed CG tolerance</source>
        <translation>オフ：CG 許容誤差を固定</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="355"/>
        <source>The finger-force error the solver holds, in percent of the converged force: it picks the loosest CG tolerance that keeps it, starting from the one above, and checks it against a converged step every so often. Off: the CG tolerance stays as set.</source>
        <translation>ソルバーが保持する指先の力の誤差（収束した力に対する割合、%）。これを満たす最も緩い CG 許容誤差を上の値から選び、ときどき収束したステップと比べて確かめます。オフ：CG 許容誤差は設定のまま。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="358"/>
        <source>State</source>
        <translation>状態</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="359"/>
        <source>Safety</source>
        <translation>安全</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="360"/>
        <source>Step time</source>
        <translation>ステップ時間</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="361"/>
        <source>CG iterations</source>
        <translation>CG 反復回数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="362"/>
        <source>Simulation rate</source>
        <translation>シミュレーション周波数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="363"/>
        <source>Tissue pace</source>
        <translation>組織の時間の進み</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="364"/>
        <source>Simulated time a wall-clock second. Below 100 % this patient&apos;s mesh is too fine for this machine to keep real time: the tissue moves in slow motion, and the solver&apos;s time step is the shortest that keeps %1 % of the pace the longest one would.</source>
        <translation>壁時計の 1 秒あたりに進むシミュレーション時間。100 % 未満では、この患者のメッシュはこの計算機で実時間を保つには細かすぎます。組織はスローモーションで動き、ソルバーの時間刻みは、最長の刻みで得られる進みの %1 % を保つ最短のものになります。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="368"/>
        <source>Haptic rate</source>
        <translation>力覚ループ周波数</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="369"/>
        <source>Apply solver settings</source>
        <translation>ソルバー設定を適用</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="370"/>
        <source>A backend change takes effect when the patient is (re)loaded.</source>
        <translation>バックエンドの変更は患者の（再）読み込み時に反映されます。</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="383"/>
        <source>stopped</source>
        <translation>停止</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="384"/>
        <source>loading</source>
        <translation>読み込み中</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="385"/>
        <source>running</source>
        <translation>実行中</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="386"/>
        <source>swapping</source>
        <translation>患者を切り替え中</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="387"/>
        <source>error: %1</source>
        <translation>エラー: %1</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="392"/>
        <source>no fault</source>
        <translation>異常なし</translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels.cpp" line="393"/>
        <source>%n backend fallback(s)</source>
        <translation>
            <numerusform>バックエンドのフォールバック %n 回</numerusform>
        </translation>
    </message>
    <message numerus="yes">
        <location filename="../ui/panels.cpp" line="394"/>
        <source>%n divergence reset(s)</source>
        <translation>
            <numerusform>発散リセット %n 回</numerusform>
        </translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="395"/>
        <source>forces held and blended</source>
        <translation>力を保持して切り替え中</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="399"/>
        <source>%1 ms</source>
        <translation>%1 ms</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="401"/>
        <location filename="../ui/panels.cpp" line="407"/>
        <source>%1 Hz</source>
        <translation>%1 Hz</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="405"/>
        <source>%1 % of real time, dt %2 ms</source>
        <translation>実時間の %1 %、dt %2 ms</translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourEditor</name>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Tumour (paper, 107 kPa)</source>
        <translation>腫瘍（論文、107 kPa）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="13"/>
        <source>Ueda et al., paper section 4.1</source>
        <translation>上田ら、論文 4.1 節</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Invasive ductal carcinoma (Krouskop, 5%)</source>
        <translation>浸潤性乳管癌（Krouskop、5%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="14"/>
        <source>Krouskop et al. 1998: 93-112 kPa at 5% precompression</source>
        <translation>Krouskop ら 1998: 5% 予圧縮で 93-112 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Invasive ductal carcinoma (Krouskop, 20%)</source>
        <translation>浸潤性乳管癌（Krouskop、20%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="15"/>
        <source>Krouskop et al. 1998: 460-558 kPa at 20% precompression</source>
        <translation>Krouskop ら 1998: 20% 予圧縮で 460-558 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Fibrous tissue (Krouskop, 5%)</source>
        <translation>線維組織（Krouskop、5%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="16"/>
        <source>Krouskop et al. 1998: 96-116 kPa at 5% precompression</source>
        <translation>Krouskop ら 1998: 5% 予圧縮で 96-116 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>DCIS (Krouskop, 20%)</source>
        <translation>DCIS（Krouskop、20%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="17"/>
        <source>Krouskop et al. 1998: 291-307 kPa at 20% precompression</source>
        <translation>Krouskop ら 1998: 20% 予圧縮で 291-307 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Fibroglandular (Krouskop, 5%)</source>
        <translation>線維腺組織（Krouskop、5%）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="18"/>
        <source>Krouskop et al. 1998: 28-35 kPa at 5% precompression</source>
        <translation>Krouskop ら 1998: 5% 予圧縮で 28-35 kPa</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="19"/>
        <source>IDC high grade (Samani)</source>
        <translation>高悪性度 IDC（Samani）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="19"/>
        <source>Samani et al. 2007: 10-43 kPa by grade, small strain</source>
        <translation>Samani ら 2007: 悪性度により 10-43 kPa、微小ひずみ</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="20"/>
        <source>Fibroadenoma (Samani, 2x fat)</source>
        <translation>線維腺腫（Samani、脂肪の 2 倍）</translation>
    </message>
    <message>
        <location filename="../ui/tumour_editor.cpp" line="20"/>
        <source>Samani et al. 2007: about 6.4 kPa</source>
        <translation>Samani ら 2007: 約 6.4 kPa</translation>
    </message>
</context>
<context>
    <name>palpation::ui::TumourPanel</name>
    <message>
        <location filename="../ui/panels.cpp" line="247"/>
        <location filename="../ui/panels.cpp" line="275"/>
        <source>Source: %1</source>
        <translation>出典: %1</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="276"/>
        <source>Preset</source>
        <translation>プリセット</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="277"/>
        <source>Stiffness</source>
        <translation>硬さ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="278"/>
        <source>Add by shape</source>
        <translation>形状で追加</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="279"/>
        <source>Sphere</source>
        <translation>球</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="280"/>
        <source>Ellipsoid</source>
        <translation>楕円体</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="281"/>
        <source>Shape</source>
        <translation>形状</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="282"/>
        <source>Centre x, y, z</source>
        <translation>中心 x, y, z</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="283"/>
        <source>Radius (x, y, z)</source>
        <translation>半径 (x, y, z)</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="284"/>
        <source>Add tumour</source>
        <translation>腫瘍を追加</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="285"/>
        <source>Remove selected</source>
        <translation>選択を削除</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="286"/>
        <source>Brush</source>
        <translation>ブラシ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="287"/>
        <source>Radius</source>
        <translation>半径</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="288"/>
        <source>Depth below the skin</source>
        <translation>皮膚からの深さ</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="289"/>
        <source>Paint</source>
        <translation>描画</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="290"/>
        <source>Erase</source>
        <translation>消去</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="291"/>
        <source>Drag on the breast to paint tumour tissue (one undo step per stroke)</source>
        <translation>乳房上をドラッグして腫瘍組織を描画（1 ストロークで 1 回の取り消し）</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="292"/>
        <source>Drag on the breast to restore healthy tissue</source>
        <translation>乳房上をドラッグして正常組織に戻す</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="293"/>
        <source>Undo</source>
        <translation>元に戻す</translation>
    </message>
    <message>
        <location filename="../ui/panels.cpp" line="294"/>
        <source>Redo</source>
        <translation>やり直し</translation>
    </message>
</context>
<context>
    <name>palpation::ui::VtkView</name>
    <message>
        <location filename="../ui/vtk_view.cpp" line="630"/>
        <source>no OpenGL context for a native window on this platform (%1)</source>
        <translation>このプラットフォーム（%1）ではネイティブウィンドウの OpenGL コンテキストを作れません</translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="633"/>
        <source>the display&apos;s OpenGL (%1) has no stereo buffers; quad-buffer stereo needs a stereo-capable GPU, driver and display</source>
        <translation>このディスプレイの OpenGL（%1）にはステレオバッファがありません。クアッドバッファ立体視にはステレオ対応の GPU、ドライバ、ディスプレイが必要です</translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="847"/>
        <source>Quad-buffer stereo is not available: %1. Showing anaglyph (red/cyan glasses) instead; side-by-side and interlaced are also available.</source>
        <translation>クアッドバッファ立体視は使えません: %1。代わりにアナグリフ（赤青メガネ）で表示します。サイドバイサイドとインターレースも使えます。</translation>
    </message>
    <message>
        <location filename="../ui/vtk_view.cpp" line="849"/>
        <source>the view is not initialised yet</source>
        <translation>ビューがまだ初期化されていません</translation>
    </message>
</context>
</TS>
